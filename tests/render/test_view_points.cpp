// skyview render --points-out: the visible points as LAS 1.4, read back by skyview's own reader
// (count, coordinates, CRS) and by a raw look at the extra bytes, then gridded by skyview dsm.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include "core/cli_run.h"
#include "core/test_support.h"
#include "render_test_support.h"
#include "skyview/dsm/las_file.h"
#include "skyview/raster/raster_read.h"
#include "skyview/render/view_points.h"
#include "temp_dir.h"

using namespace skyview;
using namespace skyview::test;

TEST(RenderPoints, RoundTripThroughTheLasReader) {
  Scene s = canyon_scene(10, 10, 200);
  s.origin = {500123.25, 5400456.5, 35.0};
  s.crs_wkt = wkt_of("EPSG:25833");
  const RayScene rays(s);
  CameraSpec spec;
  spec.position = {s.origin[0] - 40, s.origin[1] + 3, s.origin[2] + 25};
  spec.look_at = {s.origin[0], s.origin[1], s.origin[2]};
  spec.width = 64;
  spec.height = 48;
  const Camera camera(spec, s.origin);
  const ViewBuffers view = render_view_buffers(rays, camera);
  ASSERT_GT(view.hits(), 1000u);
  ASSERT_LT(view.hits(), view.position.size());  // some sky: those pixels are left out
  std::vector<float> a(view.position.size()), b(view.position.size());
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = 0.001f * float(i), b[i] = -float(i);
  ViewPointsOptions po;
  po.attributes = {{"svf", "unitless", a.data()}, {"exposure", "kWh m-2", b.data()}};
  po.intensity = a.data();
  const std::string path = temp_dir("render-points") + "/view.las";
  ASSERT_EQ(write_view_points(path, view, s, po), view.hits());

  const LasReader reader = LasReader::open_file(path);
  const LasHeader& h = reader.header();
  EXPECT_EQ(h.version_minor, 4);
  EXPECT_EQ(h.point_format, 6);
  EXPECT_EQ(h.record_length, 30 + 2 * 4);
  EXPECT_EQ(h.point_count, view.hits());
  EXPECT_NE(h.crs_wkt.find("25833"), std::string::npos) << h.crs_wkt;
  std::vector<LasPoint> points;
  reader.read_points([&](const std::vector<LasPoint>& c) { points.insert(points.end(), c.begin(), c.end()); });
  ASSERT_EQ(points.size(), view.hits());
  // The points in pixel order, each at the position buffer's hit within half a LAS step (and the
  // float precision of a scene-local coordinate).
  std::size_t k = 0;
  std::vector<std::size_t> pixel;
  for (std::size_t i = 0; i < view.position.size(); ++i) {
    if (!view.hit(i)) continue;
    pixel.push_back(i);
    for (int c = 0; c < 3; ++c) {
      const double world = s.origin[c] + view.position[i][c];
      const double got = c == 0 ? points[k].x : c == 1 ? points[k].y : points[k].z;
      ASSERT_NEAR(got, world, 0.0005 + 1e-6) << "point " << k << " axis " << c;
    }
    EXPECT_EQ(points[k].intensity, std::lround(std::min(1.0f, a[i]) * 65535));
    ++k;
  }
  // The extra bytes: their descriptors by name and each point's values after its 30 bytes.
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t vlr = bytes.find("LASF_Spec");
  ASSERT_NE(vlr, std::string::npos);
  EXPECT_EQ(std::string(bytes.c_str() + vlr - 2 + 54 + 4), "svf");
  EXPECT_EQ(std::string(bytes.c_str() + vlr - 2 + 54 + 192 + 4), "exposure");
  for (std::size_t j : {std::size_t(0), points.size() / 2, points.size() - 1}) {
    float v[2];
    std::memcpy(v, bytes.data() + h.point_offset + j * h.record_length + 30, sizeof v);
    EXPECT_EQ(v[0], a[pixel[j]]);
    EXPECT_EQ(v[1], b[pixel[j]]);
  }
}

// From the command line: the cloud of a view from above, gridded by skyview dsm, gives the house's
// roof and the ground back.
TEST(RenderPoints, CommandLineCloudGridsBackToTheScene) {
  const std::string dir = temp_dir("render-points-cli");
  Scene s;
  s.meshes.push_back(ground_mesh(60));
  s.meshes.push_back(box_mesh("house", {20, 20, 0}, {30, 30, 8}));
  write_obj(s, dir + "/house.obj");
  const std::string las = dir + "/view.las";
  RunResult r = run_skyview("render " + dir + "/house.obj " + dir +
                                "/view.tif --s_srs EPSG:25833 --camera 25,25,100 --look-at 25,25,0 --up 0,1,0 "
                                "--orthographic 40 --size 80x80 --directions 4 --samples 4 --points-out " +
                                las,
                            dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const LasReader reader = LasReader::open_file(las);
  EXPECT_EQ(reader.header().point_count, 80u * 80u);  // the ground fills the view
  EXPECT_FALSE(reader.header().crs_wkt.empty());
  // Existing outputs are kept without --overwrite.
  r = run_skyview("render " + dir + "/house.obj " + dir +
                      "/view2.tif --camera 25,25,100 --look-at 25,25,0 --up 0,1,0 --orthographic 40 --size 8x8 "
                      "--points-out " +
                      las,
                  dir);
  EXPECT_EQ(r.exit_code, 1);
  r = run_skyview("dsm " + dir + "/grid.tif --points " + las + " --res 1", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RasterBand grid = read_band(dir + "/grid.tif", 1);
  ASSERT_TRUE(grid.georef.has_geotransform);
  const auto value_at = [&](double x, double y) {
    const auto& g = grid.georef.geotransform;
    return grid.values(int((x - g[0]) / g[1]), int((y - g[3]) / g[5]));
  };
  EXPECT_NEAR(value_at(25.5, 25.5), 8.0, 1e-3);
  EXPECT_NEAR(value_at(10.5, 10.5), 0.0, 1e-3);
}
