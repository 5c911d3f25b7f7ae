// `skyview exposure` from the command line: its bands and metadata, a sky read from a skymap
// file, and one error line for each bad input a careless user types.
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "core/cli_run.h"
#include "core/test_support.h"
#include "exposure_test_support.h"

namespace skyview {
namespace {

// A small UTM DSM (57.7° N, 15° E): a 12 m block in a plane, 2 m cells.
std::string write_dsm(const std::string& dir, bool with_crs = true) {
  GeoReference g;
  g.geotransform = {500000.0, 2.0, 0.0, 6400000.0, 0.0, -2.0};
  g.has_geotransform = true;
  if (with_crs) g.crs_wkt = test::wkt_of("EPSG:32633");
  const Terrain t =
      rasterize([](double e, double n) { return std::abs(e) < 8 && std::abs(n) < 8 ? 12.0 : 0.0; }, 31, 31, g);
  const std::string path = dir + (with_crs ? "/dsm.tif" : "/nocrs.tif");
  write_terrain(path, t, WriteOptions{});
  return path;
}

const char* const kDay = " --from 2024-06-21T00:00Z --to 2024-06-22T00:00Z --step 1h --map-size 64";

TEST(ExposureCli, WritesItsBandsWithUnitsAndTheRunsParameters) {
  const std::string dir = test::temp_dir("exposure-cli");
  const std::string dsm = write_dsm(dir), out = dir + "/e.tif";
  const test::RunResult r =
      test::run_skyview("exposure " + dsm + " " + out + kDay + " --preview " + dir + "/e.png", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir + "/e.png"));
  init_gdal();
  GDALDatasetUniquePtr ds(GDALDataset::Open(out.c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(ds);
  ASSERT_EQ(ds->GetRasterCount(), 6);
  const char* names[] = {"total", "direct", "diffuse", "reflected", "horizontal_total", "svf"};
  for (int b = 0; b < 6; ++b) {
    EXPECT_STREQ(ds->GetRasterBand(b + 1)->GetDescription(), names[b]);
    EXPECT_STREQ(ds->GetRasterBand(b + 1)->GetUnitType(), b < 5 ? "kWh m-2" : "1");
  }
  EXPECT_STREQ(ds->GetMetadataItem("EXPOSURE_METHOD"), "fast");
  EXPECT_STREQ(ds->GetMetadataItem("SITE_SOURCE"), "the raster's centre");
  EXPECT_STREQ(ds->GetMetadataItem("SKY_FROM_UTC"), "2024-06-21T00:00:00Z");
  EXPECT_NE(ds->GetMetadataItem("SKY_LATITUDE"), nullptr);
  EXPECT_STREQ(ds->GetMetadataItem("ALBEDO"), "0.2");
  // A cell in the open plane: total = horizontal_total = the unobstructed global horizontal.
  float total = 0, horizontal = 0;
  ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Read, 1, 1, 1, 1, &total, 1, 1, GDT_Float32, 0, 0), CE_None);
  ASSERT_EQ(ds->GetRasterBand(5)->RasterIO(GF_Read, 1, 1, 1, 1, &horizontal, 1, 1, GDT_Float32, 0, 0), CE_None);
  const double open = std::stod(ds->GetMetadataItem("GLOBAL_HORIZONTAL_UNOBSTRUCTED_KWH_M2"));
  EXPECT_GT(open, 5.0);  // kWh/m², a clear midsummer day
  EXPECT_NEAR(horizontal, open, 0.01 * open);
}

TEST(ExposureCli, ReadsItsSkyFromASkymapFileForBothMethods) {
  const std::string dir = test::temp_dir("exposure-cli");
  const std::string dsm = write_dsm(dir), map = dir + "/sky.tif";
  ASSERT_EQ(test::run_skyview("skymap " + map +
                                  " --no-preview --lat 57.7 --lon 15 --from 2024-06-21T00:00Z --to 2024-06-22T00:00Z "
                                  "--step 1h --size 64",
                              dir)
                .exit_code,
            0);
  for (const char* method : {"fast", "exact"}) {
    const std::string out = dir + "/" + method + ".tif";
    const test::RunResult r =
        test::run_skyview("exposure " + dsm + " " + out + " --skymap " + map + " --method " + method, dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    init_gdal();
    GDALDatasetUniquePtr ds(GDALDataset::Open(out.c_str(), GDAL_OF_RASTER));
    ASSERT_TRUE(ds);
    EXPECT_STREQ(ds->GetMetadataItem("SKYMAP"), map.c_str());
    EXPECT_STREQ(ds->GetMetadataItem("SKY_LATITUDE"), "57.7");
  }
}

TEST(ExposureCli, BadInputIsOneErrorLine) {
  const std::string dir = test::temp_dir("exposure-cli");
  const std::string dsm = write_dsm(dir), nocrs = write_dsm(dir, false), out = " " + dir + "/x.tif";
  const std::string map = dir + "/sky.tif";
  ASSERT_EQ(test::run_skyview("skymap " + map +
                                  " --no-preview --lat 10 --lon 15 --from 2024-06-21T00:00Z --to 2024-06-22T00:00Z "
                                  "--size 32",
                              dir)
                .exit_code,
            0);
  struct Case {
    std::string args, message;
    int exit_code = 1;  // 2 for a bad command line
  };
  const Case cases[] = {
      {"exposure " + dsm + out + " --from 2024-06-21T00:00Z --to 2024-06-21T00:00Z", "the period is empty"},
      {"exposure " + dsm + out +
           " --from 2024-12-21T10:00Z --to 2024-12-21T12:00Z --lat 80 --lon 15 "
           "--allow-site-mismatch",
       "no daylight at 80, 15"},
      {"exposure " + dsm + out + " --skymap " + dsm, "is not a sky map written by skyview skymap"},
      {"exposure " + dsm + out + " --from -2500-01-01T00:00Z --to 2024-01-01T00:00Z", "outside -2000..6000", 2},
      {"exposure " + dsm + out + " --skymap " + map, "degrees from the raster's centre"},
      {"exposure " + dsm + out + kDay + " --albedo 1.5", "--albedo must be within 0 .. 1", 2},
      {"exposure " + dsm + out + kDay + " --method slow", "--method must be fast or exact", 2},
      {"exposure " + dsm + out + " --skymap " + map + " --turbidity 3", "--turbidity applies only to runs without", 2},
      {"exposure " + dsm + out + kDay + " --method exact --reads mipmap", "--reads applies only to --method fast", 2},
      {"exposure " + dsm + out + kDay + " --rays 16", "--rays applies only to --horizon-method raycast", 2},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    test::expect_one_line_error(test::run_skyview(c.args, dir), c.message, c.exit_code);
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.tif"));
  }
  // A raster without a CRS is warned about when read, then refused: one warning, one error.
  const test::RunResult r = test::run_skyview("exposure " + nocrs + out + kDay, dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("has no CRS to place the sun: give --lat and --lon"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 2) << r.err;
}

}  // namespace
}  // namespace skyview
