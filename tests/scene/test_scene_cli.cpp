// `skyview scene`: its JSON summary, the PLY it writes (read back through Assimp), and the one-line
// errors a careless command line gets.
#include <nlohmann/json.hpp>

#include <cstdio>

#include "core/cli_run.h"
#include "scene_test_support.h"
#include "skyview/scene/scene_output.h"

using namespace skyview;
using namespace skyview::test;

namespace {

// Standard output of `skyview ARGS` (stderr to a file beside it).
std::string skyview_stdout(const std::string& args, const std::string& dir) {
  const std::string cmd = std::string(SKYVIEW_EXE) + " " + args + " 2>" + dir + "/stderr.txt";
  std::FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  char buffer[4096];
  for (std::size_t n; pipe && (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
  if (pipe) pclose(pipe);
  return out;
}

}  // namespace

TEST(SceneCli, JsonSummaryAndPlyRoundTrip) {
  const std::string zurich = city3d_file("zurich_subset_lod2.city.json");
  REQUIRE_CITY3D(zurich);
  const std::string dir = temp_dir("scene-cli");
  const std::string ply = dir + "/zurich.ply";
  const nlohmann::json j = nlohmann::json::parse(skyview_stdout("scene " + zurich + " --json --out " + ply, dir));
  EXPECT_EQ(j["meshes"], 161);
  EXPECT_EQ(j["triangles"], 5142);
  EXPECT_EQ(j["crs"], "CH1903+ / LV95 (EPSG:2056)");
  EXPECT_NEAR(j["bounds"]["min"][0].get<double>(), 2678219.194, 2e-3);
  EXPECT_NEAR(j["bounds"]["max"][2].get<double>(), 620.905, 2e-3);
  EXPECT_EQ(j["inputs"][0]["format"], "CityJSON 1.1");
  EXPECT_EQ(j["skipped"]["meshes"], 0);
  // The PLY holds the same triangles, relative to the same origin.
  const Scene back = load_scene({ply});
  EXPECT_EQ(back.triangle_count(), 5142u);
  const auto b = back.bounds();
  EXPECT_NEAR(b[0][0] + back.origin[0] + j["origin"][0].get<double>(), 2678219.194, 2e-3);
  EXPECT_NEAR(b[1][2] + back.origin[2], 620.905, 2e-3);
  // An existing output is kept without --overwrite.
  expect_one_line_error(run_skyview("scene " + zurich + " --out " + ply, dir), "exists");
  EXPECT_EQ(run_skyview("scene " + zurich + " --out " + ply + " --overwrite", dir).exit_code, 0);
}

TEST(SceneCli, CarelessCommandLines) {
  const std::string zurich = city3d_file("zurich_subset_lod2.city.json");
  REQUIRE_CITY3D(zurich);
  const std::string dir = temp_dir("scene-cli");
  expect_one_line_error(run_skyview("scene", dir), "inputs is required", 2);
  expect_one_line_error(run_skyview("scene " + dir + "/missing.city.json", dir), "no such file");
  expect_one_line_error(run_skyview("scene " + zurich + " --out " + dir + "/scene.obj", dir), "must end in .ply", 2);
  expect_one_line_error(run_skyview("scene " + zurich + " --out " + zurich, dir), "must end in .ply", 2);
  expect_one_line_error(run_skyview("scene " + zurich + " --height-field h", dir), "--height-field applies only to", 2);
  expect_one_line_error(run_skyview("scene " + zurich + " --z-scale 0.3048", dir), "--z-scale applies only to", 2);
  expect_one_line_error(run_skyview("scene " + zurich + " --s_srs EPSG:2056", dir), "--s_srs applies only to", 2);
  expect_one_line_error(run_skyview("scene " + zurich + " --overwrite", dir), "--overwrite applies only to --out", 2);
  expect_one_line_error(run_skyview("scene " + zurich + " --t_srs EPSG:4326", dir), "not in a projected CRS");
  expect_one_line_error(run_skyview("scene " + zurich + " --up x", dir), "--up", 2);
  write_text(dir + "/notes.txt", "just words\n");
  expect_one_line_error(run_skyview("scene " + dir + "/notes.txt", dir), "cannot tell what");
}
