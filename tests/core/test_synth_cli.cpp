// `skyview synth` from the command line: outputs replace old ones only once complete, the
// footprints' format follows the extension in any case, the CRS must be projected in metres (a
// sphere too), options a kind does not use are refused, and the LAS header counts the returns.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include "cli_run.h"
#include "skyview/dsm/las_file.h"
#include "skyview/raster/raster_io.h"
#include "temp_dir.h"

using namespace skyview;
using namespace skyview::test;

namespace {

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

template <class T>
T field(const std::string& bytes, std::size_t at) {
  T v{};
  std::memcpy(&v, bytes.data() + at, sizeof v);
  return v;
}

// The names in `dir` but the runs' stderr.txt: a temporary file or folder left behind shows here.
std::set<std::string> files_in(const std::string& dir) {
  std::set<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.insert(e.path().filename().string());
  names.erase("stderr.txt");
  return names;
}

// Opens a vector output and returns its driver's name and feature count of its one layer.
std::pair<std::string, long long> vector_summary(const std::string& path) {
  GDALAllRegister();
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  if (!ds || ds->GetLayerCount() != 1) return {"", -1};
  return {ds->GetDriver()->GetDescription(), ds->GetLayer(0)->GetFeatureCount()};
}

TEST(SynthCli, LidarReplacesAnOldFileOnlyOnceComplete) {
  const std::string dir = test::temp_dir("synth");
  const std::string las = dir + "/keep.las";
  ASSERT_EQ(run_skyview("synth lidar " + las + " --size 64", dir).exit_code, 0);
  const std::string old = bytes_of(las);
  ASSERT_GT(old.size(), 160000u);  // 64 x 64 m at 2 per m²: 90 x 90 returns of 20 bytes, and 5 birds

  expect_one_line_error(run_skyview("synth lidar " + las + " --size 100", dir), "use --overwrite to replace it");
  EXPECT_EQ(bytes_of(las), old);

  // 141 x 141 returns do not fit under the limit: the write fails half-way; the old file stays whole
  // and the partial one goes.
  expect_one_line_error(run_skyview("synth lidar " + las + " --size 100 --overwrite", dir, 200000),
                        "cannot write '" + las + "'");
  EXPECT_EQ(bytes_of(las), old);
  EXPECT_EQ(files_in(dir), std::set<std::string>{"keep.las"});

  ASSERT_EQ(run_skyview("synth lidar " + las + " --size 100 --overwrite", dir).exit_code, 0);
  EXPECT_EQ(LasReader::open_file(las).header().point_count, 141u * 141u + 5u);
  EXPECT_EQ(files_in(dir), std::set<std::string>{"keep.las"});
}

TEST(SynthCli, FootprintsReplaceAnOldOutputOnlyOnceComplete) {
  const std::string dir = test::temp_dir("synth");
  const std::string json = dir + "/f.geojson";
  ASSERT_EQ(run_skyview("synth footprints " + json + " --size 64", dir).exit_code, 0);
  const std::string old = bytes_of(json);
  ASSERT_GT(old.size(), 1000u);
  // The new district is the same size in bytes but another layout: a truncated write would show.
  expect_one_line_error(run_skyview("synth footprints " + json + " --size 64 --seed 2 --overwrite", dir, 1000),
                        "cannot write '" + json + "'");
  EXPECT_EQ(bytes_of(json), old);
  EXPECT_EQ(files_in(dir), std::set<std::string>{"f.geojson"});
  ASSERT_EQ(run_skyview("synth footprints " + json + " --size 64 --seed 2 --overwrite", dir).exit_code, 0);
  EXPECT_NE(bytes_of(json), old);
  EXPECT_EQ(vector_summary(json), std::make_pair(std::string("GeoJSON"), 9LL));
  EXPECT_EQ(files_in(dir), std::set<std::string>{"f.geojson"});

  // A shapefile comes out with all its side files under the final name, and is replaced whole.
  const std::string shp = dir + "/s.shp";
  ASSERT_EQ(run_skyview("synth footprints " + shp + " --size 64", dir).exit_code, 0);
  std::ofstream(dir + "/s.qix") << "a stale spatial index of the old shapefile";
  ASSERT_EQ(run_skyview("synth footprints " + shp + " --size 64 --overwrite", dir).exit_code, 0);
  EXPECT_EQ(vector_summary(shp), std::make_pair(std::string("ESRI Shapefile"), 9LL));
  std::set<std::string> names = files_in(dir);
  names.erase("s.cpg");  // written or not, depending on GDAL's default encoding
  EXPECT_EQ(names, (std::set<std::string>{"f.geojson", "s.shp", "s.shx", "s.dbf", "s.prj"}));
}

TEST(SynthCli, FootprintsFormatFollowsTheExtensionInAnyCase) {
  const std::string dir = test::temp_dir("synth");
  const std::pair<std::string, std::string> cases[] = {
      {"F.GPKG", "GPKG"}, {"G.GeoJSON", "GeoJSON"}, {"J.JSON", "GeoJSON"}, {"S.SHP", "ESRI Shapefile"}};
  for (const auto& [name, driver] : cases) {
    const std::string path = dir + "/" + name;
    const RunResult r = run_skyview("synth footprints " + path + " --size 64", dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(vector_summary(path), std::make_pair(driver, 9LL)) << name;
  }
  // A GeoPackage is an SQLite database, never GeoJSON text.
  EXPECT_EQ(bytes_of(dir + "/F.GPKG").substr(0, 15), "SQLite format 3");
}

// A projected CRS on a sphere has an inverse flattening of 0: the sphere's flattening is 0.
TEST(SynthCli, SphericalCrsIsRasterised) {
  const std::string dir = test::temp_dir("synth");
  const std::string out = dir + "/s.tif";
  const RunResult r =
      run_skyview("synth pit " + out + " --size 11 --cell 5 --crs ESRI:53004 --origin 0 --northing 0", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RasterBand b = read_band(out, 1);
  ASSERT_EQ(b.values.width(), 11);
  ASSERT_EQ(b.values.height(), 11);
  EXPECT_NE(b.georef.crs_wkt.find("Sphere_Mercator"), std::string::npos);
  EXPECT_DOUBLE_EQ(b.georef.geotransform[0], -27.5);
  EXPECT_DOUBLE_EQ(b.georef.geotransform[1], 5.0);
  // The pit of radius 20 m around the centre cell (5, 5); Mercator's scale at the equator is 1.
  EXPECT_EQ(b.values(5, 5), -20.0f);
  EXPECT_EQ(b.values(3, 5), -20.0f);  // 10 m west
  EXPECT_EQ(b.values(5, 2), -20.0f);  // 15 m north
  EXPECT_EQ(b.values(3, 3), -20.0f);  // 14.1 m north-west
  EXPECT_EQ(b.values(0, 5), 0.0f);    // 25 m west
  EXPECT_EQ(b.values(2, 2), 0.0f);    // 21.2 m north-west
  EXPECT_EQ(b.values(10, 10), 0.0f);
}

TEST(SynthCli, CrsMustBeProjectedInMetres) {
  const std::string dir = test::temp_dir("synth");
  const std::string out = dir + "/o.tif";
  expect_one_line_error(
      run_skyview("synth plane " + out + " --size 11 --cell 10 --crs EPSG:2263 --origin 1000000 --northing 200000",
                  dir),
      "--crs must be a projected CRS in metres ('EPSG:2263' is in US survey foot)", 2);
  expect_one_line_error(run_skyview("synth lidar " + dir + "/l.las --size 64 --crs EPSG:2263", dir),
                        "is in US survey foot", 2);
  expect_one_line_error(run_skyview("synth plane " + out + " --size 11 --crs EPSG:4326", dir),
                        "--crs must be a projected CRS in metres ('EPSG:4326' is geographic)", 2);
  expect_one_line_error(run_skyview("synth plane " + out + " --size 11 --crs EPSG:32633+6360", dir),
                        "has heights in US survey foot", 2);
  // A grid placed where the CRS does not project (Albers USA, 6400 km north of its origin).
  expect_one_line_error(run_skyview("synth pit " + out + " --size 11 --crs ESRI:102003", dir),
                        "lies partly outside where its CRS projects");
  EXPECT_EQ(files_in(dir), std::set<std::string>{});
  // Metres both ways pass.
  const RunResult r = run_skyview("synth plane " + out + " --size 11 --crs EPSG:32633+5773", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(SynthCli, OptionsTheKindDoesNotUseAreRefused) {
  const std::string dir = test::temp_dir("synth");
  for (const char* kind : {"canyon", "pit", "plane"}) {
    expect_one_line_error(run_skyview(std::string("synth ") + kind + " " + dir + "/x.tif --size 11 --seed 5", dir),
                          "--seed applies only to city, mountains, lidar and footprints", 2);
  }
  expect_one_line_error(run_skyview("synth pit " + dir + "/x.tif --size 11 --density 3", dir),
                        "--density applies only to lidar", 2);
  expect_one_line_error(run_skyview("synth footprints " + dir + "/x.gpkg --size 64 --birds 3", dir),
                        "--birds applies only to lidar", 2);
  expect_one_line_error(run_skyview("synth lidar " + dir + "/x.las --size 64 --birds -1", dir),
                        "must be zero or positive", 2);
  EXPECT_EQ(files_in(dir), std::set<std::string>{});
  // The kinds with a random layout take it.
  EXPECT_EQ(run_skyview("synth city " + dir + "/c.tif --size 11 --seed 5", dir).exit_code, 0);
  EXPECT_EQ(run_skyview("synth lidar " + dir + "/l.las --size 64 --seed 5", dir).exit_code, 0);
}

TEST(SynthCli, TooDenseASurveyIsRefusedClearly) {
  const std::string dir = test::temp_dir("synth");
  const RunResult r = run_skyview("synth lidar " + dir + "/l.las --size 64 --density 1e20", dir);
  expect_one_line_error(r, "too many points: 1e+20 returns per square metre over 64 x 64 m make 4.096e+23");
  EXPECT_EQ(r.err.find("vector"), std::string::npos) << r.err;
  EXPECT_EQ(files_in(dir), std::set<std::string>{});
}

// synth lidar writes single returns: all of them are first returns, birds too.
TEST(SynthCli, LasHeaderCountsPointsByReturn) {
  const std::string dir = test::temp_dir("synth");
  const std::string las = dir + "/l.las";
  ASSERT_EQ(run_skyview("synth lidar " + las + " --size 64 --birds 7", dir).exit_code, 0);
  const std::string b = bytes_of(las);
  ASSERT_GT(b.size(), 227u);
  // 64 m at 2 per m²: returns every 1/sqrt(2) m, 90 along each side.
  EXPECT_EQ(field<std::uint32_t>(b, 107), 90u * 90u + 7u);
  EXPECT_EQ(field<std::uint32_t>(b, 111), 90u * 90u + 7u);
  for (int r = 1; r < 5; ++r) EXPECT_EQ(field<std::uint32_t>(b, 111 + 4 * r), 0u) << r;
}

// LAS 1.4 also holds 64-bit counts of returns 1..15; the legacy ones stay 0 for formats 6..10.
TEST(LasWriter, HeaderCountsPointsByReturn) {
  const std::string dir = test::temp_dir("synth");
  const std::vector<LasPoint> pts = {{0, 0, 0, 0, 1, 3, 2}, {1, 0, 0, 0, 2, 3, 2}, {2, 0, 0, 0, 3, 3, 2},
                                     {3, 0, 0, 0, 1, 2, 2}, {4, 0, 0, 0, 2, 2, 2}, {5, 0, 0, 0, 1, 1, 2},
                                     {6, 0, 0, 0, 9, 9, 2}};
  for (int format : {1, 6}) {
    LasWriteOptions o;
    o.version_minor = 4;
    o.point_format = format;
    const std::string path = dir + "/f" + std::to_string(format) + ".las";
    write_las(path, format == 1 ? std::vector<LasPoint>(pts.begin(), pts.end() - 1) : pts, o);
    const std::string b = bytes_of(path);
    const std::uint64_t expected[15] = {3, 2, 1, 0, 0, 0, 0, 0, format == 6 ? 1u : 0u};
    for (int r = 0; r < 15; ++r) EXPECT_EQ(field<std::uint64_t>(b, 255 + 8 * r), expected[r]) << format << " " << r;
    for (int r = 0; r < 5; ++r) {
      EXPECT_EQ(field<std::uint32_t>(b, 111 + 4 * r), format == 6 ? 0u : expected[r]) << format << " " << r;
    }
  }
}

}  // namespace
