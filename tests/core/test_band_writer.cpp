// BandWriter: bands written one at a time, in any order, appear at the path only when finished;
// an abandoned writer leaves nothing behind and keeps what was there. write_output_file and
// write_png: the same for files that are not georeferenced rasters.
#include <gdal_priv.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "skyview/core/error.h"
#include "test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

constexpr int kW = 7, kH = 5;

// Band b holds b * 100 + cell index, with one NaN cell per band at index b.
std::vector<float> band_values(int b) {
  std::vector<float> v(kW * kH);
  for (int i = 0; i < kW * kH; ++i) v[i] = static_cast<float>(b * 100 + i);
  v[b] = std::numeric_limits<float>::quiet_NaN();
  return v;
}

GeoReference georef() {
  GeoReference g;
  g.has_geotransform = true;
  g.geotransform = {500000, 2, 0, 6400000, 0, -2};
  g.crs_wkt = wkt_of("EPSG:32633");
  return g;
}

// A fresh folder and the output's path in it.
struct Scratch {
  std::string dir = temp_dir("bandwriter");
  std::string path = dir + "/out.tif";
};

// Band b (from 0) of `ds` holds `want`, with nodata where it is NaN.
void expect_band(GDALDataset& ds, int b, const std::vector<float>& want, float nodata) {
  std::vector<float> got(kW * kH);
  ASSERT_EQ(ds.GetRasterBand(b + 1)->RasterIO(GF_Read, 0, 0, kW, kH, got.data(), kW, kH, GDT_Float32, 0, 0), CE_None);
  for (int i = 0; i < kW * kH; ++i) {
    EXPECT_EQ(got[i], std::isnan(want[i]) ? nodata : want[i]) << "band " << b << " cell " << i;
  }
}

std::size_t files_in(const std::string& dir) {
  return static_cast<std::size_t>(
      std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()));
}

// Each test writes `path` in a fresh folder with `wo`.
class BandWriterTest : public ::testing::Test {
 protected:
  const Scratch scratch;
  const std::string& path = scratch.path;
  WriteOptions wo;
};

class BandWriterFormats : public BandWriterTest, public ::testing::WithParamInterface<const char*> {};

// GTiff is written in place band by band; COG only copies a finished dataset (the memory path).
TEST_P(BandWriterFormats, BandsInAnyOrderAppearWhenFinished) {
  wo.format = GetParam();
  wo.metadata["RUN"] = "test";
  {
    BandWriter out(path, kW, kH, 3, georef(), wo);
    for (int b : {2, 0, 1}) {
      const std::vector<float> v = band_values(b);
      out.write(b, {"band_" + std::to_string(b), "degree", v.data(), {{"INDEX", std::to_string(b)}}});
    }
    EXPECT_FALSE(std::filesystem::exists(path)) << "nothing at the path before finish()";
    out.finish();
  }
  EXPECT_EQ(files_in(scratch.dir), 1u) << "no temporary file left";
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(ds);
  ASSERT_EQ(ds->GetRasterCount(), 3);
  EXPECT_STREQ(ds->GetMetadataItem("RUN"), "test");
  double gt[6];
  ASSERT_EQ(ds->GetGeoTransform(gt), CE_None);
  EXPECT_EQ(gt[0], 500000.0);
  EXPECT_EQ(gt[5], -2.0);
  EXPECT_NE(std::string(ds->GetProjectionRef()).find("32633"), std::string::npos);
  for (int b = 0; b < 3; ++b) {
    GDALRasterBand* band = ds->GetRasterBand(b + 1);
    EXPECT_EQ(band->GetDescription(), "band_" + std::to_string(b));
    EXPECT_STREQ(band->GetUnitType(), "degree");
    EXPECT_STREQ(band->GetMetadataItem("INDEX"), std::to_string(b).c_str());
    int has_nodata = 0;
    EXPECT_EQ(band->GetNoDataValue(&has_nodata), wo.nodata);
    EXPECT_TRUE(has_nodata);
    expect_band(*ds, b, band_values(b), wo.nodata);
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, BandWriterFormats, ::testing::Values("GTiff", "COG"));

// GDAL 3.6 names netCDF variables Band1, Band2 ... with long_name "GDAL Band Number N": the
// writer renames them after the bands (xarray and CDO read variables by name), keeps GDAL's name
// where the band's would clash with a variable already there (x, the coordinate), and makes a
// description that netCDF would refuse into a name it takes.
TEST_F(BandWriterTest, NetcdfVariablesAreNamedAfterTheBands) {
  wo.format = "netCDF";
  const std::string nc = scratch.dir + "/out.nc";
  const char* names[] = {"svf", "horizon_azimuth_11.25", "x", "3d nodes/m"};
  {
    BandWriter out(nc, kW, kH, 4, georef(), wo);
    for (int b = 0; b < 4; ++b) {
      const std::vector<float> v = band_values(b);
      out.write(b, {names[b], "1", v.data(), {}});
    }
    out.finish();
  }
  EXPECT_EQ(files_in(scratch.dir), 1u) << "no temporary file left";
  {
    // GDAL's history names the file it created: the final name, not the temporary one.
    GDALDatasetUniquePtr ds(GDALDataset::Open(nc.c_str(), GDAL_OF_RASTER));
    ASSERT_TRUE(ds);
    const char* history = ds->GetMetadataItem("NC_GLOBAL#history");
    ASSERT_NE(history, nullptr);
    EXPECT_NE(std::string(history).find("Create( " + nc + ","), std::string::npos) << history;
    EXPECT_EQ(std::string(history).find("skyview-tmp"), std::string::npos) << history;
  }
  for (const auto& [b, variable] :
       {std::pair{0, "svf"}, {1, "horizon_azimuth_11.25"}, {2, "Band3"}, {3, "_3d_nodes_m"}}) {
    const std::string sub = "NETCDF:\"" + nc + "\":" + variable;
    GDALDatasetUniquePtr ds(GDALDataset::Open(sub.c_str(), GDAL_OF_RASTER));
    ASSERT_TRUE(ds) << sub;
    EXPECT_STREQ(ds->GetRasterBand(1)->GetMetadataItem("long_name"), names[b]) << sub;
    double gt[6];
    ASSERT_EQ(ds->GetGeoTransform(gt), CE_None);
    EXPECT_EQ(gt[0], 500000.0);
    expect_band(*ds, 0, band_values(b), wo.nodata);
  }
}

// ENVI's header describes the file by the name GDAL created it under: the final one, not the
// temporary name it was written under (until Dec 5, ".out.skyview-tmp-PID.bin").
TEST_F(BandWriterTest, EnviHeadersNameTheFinalFile) {
  wo.format = "ENVI";
  const std::string bin = scratch.dir + "/out.bin";
  const std::vector<float> v = band_values(0);
  write_bands(bin, kW, kH, georef(), {{"svf", "1", v.data(), {}}}, wo);
  std::ifstream in(scratch.dir + "/out.hdr");
  const std::string header((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(header.find("out.bin}"), std::string::npos) << header;
  EXPECT_EQ(header.find("skyview-tmp"), std::string::npos) << header;
}

// A band written in parts of rows (what `skyview horizon` does by blocks) equals the band whole.
TEST_F(BandWriterTest, BandsInPartsOfRows) {
  const std::vector<float> v = band_values(1);
  {
    BandWriter out(path, kW, kH, 1, georef(), wo);
    EXPECT_EQ(out.block_rows(), 256) << "GeoTIFFs are tiled 256 x 256";
    out.write_rows(0, 3, 2, v.data() + 3 * kW);
    out.write_rows(0, 0, 3, v.data());
    EXPECT_THROW(out.write_rows(0, 4, 2, v.data()), skyview::Error) << "past the last row";
    out.describe(0, {"parts", "degree", nullptr, {}});
    out.finish();
  }
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(ds);
  EXPECT_STREQ(ds->GetRasterBand(1)->GetDescription(), "parts");
  expect_band(*ds, 0, v, wo.nodata);
}

TEST_F(BandWriterTest, AbandonedLeavesNothingAndKeepsTheOldOutput) {
  const std::vector<float> v = band_values(0);
  {
    BandWriter out(path, kW, kH, 2, georef(), wo);
    out.write(0, {"a", "1", v.data(), {}});
  }  // an error between bands: never finished
  EXPECT_EQ(files_in(scratch.dir), 0u);

  std::ofstream(path) << "an older output";
  EXPECT_THROW(BandWriter(path, kW, kH, 1, georef(), wo), skyview::Error) << "exists, and no overwrite";
  wo.overwrite = true;
  {
    BandWriter out(path, kW, kH, 1, georef(), wo);
    out.write(0, {"a", "1", v.data(), {}});
  }
  EXPECT_EQ(files_in(scratch.dir), 1u);
  std::ifstream in(path);
  std::string old((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(old, "an older output");
}

// Reports and plots go the same way: nothing replaced without overwrite, no temporary left.
TEST(OutputFile, ReplacesOnlyWithOverwriteAndLeavesNoTemporary) {
  const Scratch scratch;
  auto contents = [&] {
    std::ifstream in(scratch.path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  const std::string bytes("a\0b\n", 4);
  write_output_file(scratch.path, bytes, false);
  EXPECT_EQ(contents(), bytes);
  EXPECT_THROW(write_output_file(scratch.path, "new", false), skyview::Error);
  EXPECT_EQ(contents(), bytes);
  write_output_file(scratch.path, "new", true);
  EXPECT_EQ(contents(), "new");
  EXPECT_EQ(files_in(scratch.dir), 1u);
  EXPECT_THROW(write_output_file(scratch.dir + "/no/such/folder.json", "x", true), skyview::Error);
}

// Pictures (previews, plots) through GDAL's PNG driver: interleaved samples land in their bands in
// order (red first), and an existing picture is kept without overwrite.
TEST(OutputFile, PngKeepsChannelOrderAndRefusesToReplace) {
  const Scratch scratch;
  const std::string path = scratch.dir + "/picture.png";
  constexpr int kW2 = 3, kH2 = 2;
  std::vector<std::uint8_t> rgb(kW2 * kH2 * 3);
  for (int i = 0; i < kW2 * kH2; ++i) {
    rgb[3 * i] = static_cast<std::uint8_t>(10 * i);       // red
    rgb[3 * i + 1] = static_cast<std::uint8_t>(100 + i);  // green
    rgb[3 * i + 2] = static_cast<std::uint8_t>(250 - i);  // blue
  }
  write_png(path, kW2, kH2, 3, rgb.data(), false);
  EXPECT_EQ(files_in(scratch.dir), 1u);  // no temporary, no .aux.xml beside it
  {
    std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    ASSERT_TRUE(ds);
    EXPECT_STREQ(ds->GetDriver()->GetDescription(), "PNG");
    ASSERT_EQ(ds->GetRasterCount(), 3);
    ASSERT_EQ(ds->GetRasterXSize(), kW2);
    ASSERT_EQ(ds->GetRasterYSize(), kH2);
    for (int b = 0; b < 3; ++b) {
      std::vector<std::uint8_t> band(kW2 * kH2);
      ASSERT_EQ(ds->GetRasterBand(b + 1)->RasterIO(GF_Read, 0, 0, kW2, kH2, band.data(), kW2, kH2, GDT_Byte, 0, 0),
                CE_None);
      for (int i = 0; i < kW2 * kH2; ++i) EXPECT_EQ(band[i], rgb[3 * i + b]) << "band " << b + 1 << " pixel " << i;
    }
  }
  const std::vector<std::uint8_t> grey(kW2 * kH2, 7);
  EXPECT_THROW(write_png(path, kW2, kH2, 1, grey.data(), false), skyview::Error);
  write_png(path, kW2, kH2, 1, grey.data(), true);
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  ASSERT_TRUE(ds);
  EXPECT_EQ(ds->GetRasterCount(), 1);
  ds.reset();
  EXPECT_EQ(files_in(scratch.dir), 1u);
}

}  // namespace
