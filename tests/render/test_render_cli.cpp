// `skyview render` from the command line: its bands, the zenith map it saves and reuses, and the
// one-line errors of careless command lines.
#include <algorithm>
#include <cmath>

#include "core/cli_run.h"
#include "render_test_support.h"
#include "scene/scene_test_support.h"
#include "skyview/raster/raster_read.h"
#include "temp_dir.h"

using namespace skyview;
using namespace skyview::test;

namespace {

std::string porch_obj(const std::string& dir) {
  Scene s = porch_scene();
  s.meshes.push_back(box_mesh("house", {20, 20, 0}, {30, 30, 8}));
  const std::string path = dir + "/porch.obj";
  write_obj(s, path);
  return path;
}

const char* kView = " --camera -20,0.5,1.5 --look-at 0,0.5,0 --fov 20 --size 41x31";

}  // namespace

TEST(RenderCli, BandsZenithReuseAndReference) {
  const std::string dir = temp_dir("render-cli");
  const std::string obj = porch_obj(dir);
  const std::string out = dir + "/view.tif", z = dir + "/zenith.tif";
  RunResult r = run_skyview("render " + obj + " " + out + kView + " --zenith-res 0.5 --save-zenith " + z +
                                " --reference --reference-rays 256 --preview " + dir + "/view.png --diff-preview " +
                                dir + "/diff.png",
                            dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RasterBand svf = read_band(out, 1);
  EXPECT_EQ(svf.description, "svf");
  EXPECT_EQ(svf.values.width(), 41);
  EXPECT_FALSE(svf.georef.has_geotransform);
  EXPECT_EQ(read_band(out, 4).description, "depth");
  EXPECT_EQ(read_band(out, 7).description, "normal_z");
  const RasterBand ref = read_band(out, 8);
  EXPECT_EQ(ref.description, "svf_reference");
  EXPECT_NEAR(ref.values(20, 15), read_band(out, 2).values(20, 15), 0.1);  // under the porch
  EXPECT_NEAR(read_band(out, 4).values(20, 15), std::hypot(20.0, 1.5), 0.3);
  // The zenith map: three layers under the slab, georeferenced.
  const RasterBand layer2 = read_band(z, 2);
  EXPECT_TRUE(layer2.georef.has_geotransform);
  EXPECT_EQ(layer2.description, "layer_2");
  // Reused, it gives the same image.
  const std::string again = dir + "/again.tif";
  r = run_skyview("render " + obj + " " + again + kView + " --zenith " + z, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto a = read_band(again, 2).values.values(), b = read_band(out, 2).values.values();
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::isnan(a[i]) != std::isnan(b[i]) || (!std::isnan(a[i]) && a[i] != b[i])) FAIL() << "pixel " << i;
  }
}

TEST(RenderCli, CarelessCommandLines) {
  const std::string dir = temp_dir("render-cli");
  const std::string obj = porch_obj(dir);
  const std::string out = " " + dir + "/out.tif";
  expect_one_line_error(run_skyview("render " + obj + out + " --camera 1,2,3 --look-at 1,2,3", dir),
                        "--look-at must differ from --camera", 2);
  expect_one_line_error(run_skyview("render " + obj + out + " --camera -20,0,2 --look-at 0,0,0 --fov 0", dir),
                        "--fov must be above 0", 2);
  expect_one_line_error(run_skyview("render " + obj + out + " --camera -20,0,2 --look-at 0,0,0 --fov 180", dir),
                        "--fov must be above 0", 2);
  expect_one_line_error(run_skyview("render " + obj + out + " --camera -20,0,2 --look-at 0,0,0 --size 800", dir),
                        "--size must be WIDTHxHEIGHT", 2);
  expect_one_line_error(run_skyview("render " + obj + out + " --camera 25,25,4 --look-at 0,0,0", dir),
                        "inside an object", 2);
  expect_one_line_error(run_skyview("render " + obj + out + " --camera -20,0,2", dir), "--look-at is required", 2);
  expect_one_line_error(run_skyview("render " + obj + " --camera -20,0,2 --look-at 0,0,0", dir), "at least one scene",
                        2);
  expect_one_line_error(
      run_skyview("render " + obj + out + " --camera -20,0,2 --look-at 0,0,0 --diff-preview " + dir + "/d.png", dir),
      "--diff-preview applies only to", 2);
  write_text(dir + "/empty.obj", "# nothing\nv 0 0 0\n");
  const RunResult empty = run_skyview("render " + dir + "/empty.obj" + out + " --camera -20,0,2 --look-at 0,0,0", dir);
  EXPECT_EQ(empty.exit_code, 1) << empty.err;
  EXPECT_EQ(std::count(empty.err.begin(), empty.err.end(), '\n'), 1) << empty.err;
}
