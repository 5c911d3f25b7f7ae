// skyview points, fisheye and fisheye-svf from the command line: outputs, a round trip, bad input.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "core/cli_run.h"
#include "core/test_support.h"

namespace skyview {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(PointsCli, CsvRowsGetValuesAndBadRowsTheirReasonWhileTheOthersAreComputed) {
  const std::string dir = test::temp_dir("points-cli");
  const std::string city = std::string(SKYVIEW_SOURCE_DIR) + "/sample_dems/city.tif";
  // city.tif: 401 x 401 one-metre cells from (499799.5, 6400200.5).
  std::ofstream(dir + "/p.csv") << "name,x,y\n"
                                   "a,500000,6400000\n"
                                   "b,abc,6400000\n"
                                   "c,400000,6400000\n"
                                   "d,500010.5,6400020.25\n";
  const test::RunResult r =
      test::run_skyview("points " + city + " " + dir + "/p.csv " + dir + "/out.csv --directions 32", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("line 3: x 'abc' is not a number"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("line 4: point (400000, 6400000) is outside the raster"), std::string::npos) << r.err;
  const std::string out = read_text(dir + "/out.csv");
  EXPECT_NE(out.find("name,x,y,svf,svf_surface,sky_visibility,ground_m,eye_m,error"), std::string::npos) << out;
  std::istringstream lines(out);
  std::string header, a, b, c, d;
  std::getline(lines, header), std::getline(lines, a), std::getline(lines, b), std::getline(lines, c),
      std::getline(lines, d);
  EXPECT_EQ(a.find("a,500000,6400000,0."), 0u) << a;
  EXPECT_EQ(b.find("b,abc,6400000,,,,,,"), 0u) << b;
  EXPECT_EQ(d.find("d,500010.5,6400020.25,0."), 0u) << d;
  // A CSV without coordinate columns, and one whose named column is missing.
  std::ofstream(dir + "/bad.csv") << "name,east,north\na,1,2\n";
  test::expect_one_line_error(test::run_skyview("points " + city + " " + dir + "/bad.csv " + dir + "/o2.csv", dir),
                              "has no coordinate columns");
  test::expect_one_line_error(
      test::run_skyview("points " + city + " " + dir + "/bad.csv " + dir + "/o2.csv --x-column east --y-column up",
                        dir),
      "has no column 'up'");
  test::expect_one_line_error(test::run_skyview("points " + city + " " + dir + "/p.csv " + dir + "/o2.txt", dir),
                              "must end in .csv or .gpkg");
}

TEST(PointsCli, GothenburgObservationPointsAsGeoPackageWithProfiles) {
  const std::string dsm = std::string(SKYVIEW_SHARED_DIR) + "/sample_data/city_goteborg/DSM_KRbig.tif";
  const std::string poi = std::string(SKYVIEW_SHARED_DIR) + "/sample_data/city_goteborg/poi_gbg.shp";
  if (!std::filesystem::exists(poi)) GTEST_SKIP() << "no Gothenburg sample under " SKYVIEW_SHARED_DIR;
  const std::string dir = test::temp_dir("points-gbg");
  const test::RunResult r = test::run_skyview(
      "points " + dsm + " " + poi + " " + dir + "/poi.gpkg --profile --profile-png " + dir + "/poi.png", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir + "/poi.png"));
  const test::RunResult csv = test::run_skyview("points " + dsm + " " + poi + " " + dir + "/poi.csv", dir);
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  const std::string out = read_text(dir + "/poi.csv");
  // The courtyard between buildings sees less sky than the park (both plausible for a dense block).
  const auto value = [&](const std::string& name) {
    const std::size_t at = out.find(name + ",");
    return std::stod(out.substr(at + name.size() + 1));
  };
  EXPECT_GT(value("courtyard"), 0.5);
  EXPECT_LT(value("courtyard"), value("park"));
  EXPECT_LT(value("park"), 0.95);
}

TEST(FisheyeCli, RenderedMaskReadsBackToThePointsSvfAndBadInputIsRefused) {
  const std::string dir = test::temp_dir("fisheye-cli");
  const std::string city = std::string(SKYVIEW_SOURCE_DIR) + "/sample_dems/city.tif";
  const test::RunResult r =
      test::run_skyview("fisheye " + city + " " + dir + "/v.png --at 500000,6400000 --size 256", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(std::filesystem::exists(dir + "/v_mask.png"));
  const std::string json = dir + "/svf.json";
  ASSERT_EQ(std::system(
                (std::string(SKYVIEW_EXE) + " fisheye-svf " + dir + "/v_mask.png --mask --json -q > " + json).c_str()),
            0);
  const std::string j = read_text(json);
  for (const char* key : {"\"svf\":", "\"svf_annulus\":", "\"sky_visibility\":", "\"center\":[", "\"radius\":"})
    EXPECT_NE(j.find(key), std::string::npos) << j;
  std::ofstream(dir + "/p.csv") << "x,y\n500000,6400000\n";
  ASSERT_EQ(test::run_skyview("points " + city + " " + dir + "/p.csv " + dir + "/p_out.csv", dir).exit_code, 0);
  const std::string p = read_text(dir + "/p_out.csv");
  // The row after the header: x,y,svf,...
  const std::string row = p.substr(p.find('\n') + 1);
  const double svf_points = std::stod(row.substr(row.find(',', row.find(',') + 1) + 1));
  const double svf_mask = std::stod(j.substr(j.find("\"svf\":") + 6));
  EXPECT_NEAR(svf_mask, svf_points, 0.01);
  // Bad input: a point outside the raster, a non-image, an image with no circle.
  test::expect_one_line_error(test::run_skyview("fisheye " + city + " " + dir + "/w.png --at 0,0 --size 128", dir),
                              "is outside the raster");
  std::ofstream(dir + "/not_an_image.jpg") << "hello";
  test::expect_one_line_error(test::run_skyview("fisheye-svf " + dir + "/not_an_image.jpg", dir), "cannot read");
  const std::vector<std::uint8_t> grey(64 * 64 * 3, 128);
  write_png(dir + "/grey.png", 64, 64, 3, grey.data(), false);
  test::expect_one_line_error(test::run_skyview("fisheye-svf " + dir + "/grey.png", dir), "no image circle found");
  // A DEM is not a picture; a one-band picture is a mask.
  test::expect_one_line_error(test::run_skyview("fisheye-svf " + city, dir), "holds Float32 values");
  test::expect_one_line_error(test::run_skyview("fisheye-svf " + dir + "/v_mask.png", dir), "read it with --mask");
}

}  // namespace
}  // namespace skyview
