// The real rasters of ../shared/sample_data: read from there, never copied; skipped with a
// message where that folder is absent.
#include <filesystem>

#include "skyview/benchmark/method_benchmark.h"
#include "test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

std::string shared_file(const std::string& rel) {
  const std::string path = std::string(SKYVIEW_SHARED_DIR) + "/sample_data/" + rel;
  return std::filesystem::exists(path) ? path : std::string();
}

#define REQUIRE_SHARED(path) \
  if ((path).empty()) GTEST_SKIP() << "../shared/sample_data is absent: real-data test skipped"

// `near_steps` and `far_lines` for the sweep: 0 keeps the defaults (64 and 1).
SkyViewProducts products_of(const Terrain& t, const std::string& method, int directions, int near_steps = 0,
                            int far_lines = 0) {
  HorizonParams p;
  p.directions = directions;
  if (near_steps > 0) p.samples = near_steps;
  if (far_lines > 0) p.far_lines = far_lines;
  p.rays = 0;
  p.curvature = "off";
  if (method == "march") p.radius = 1000.0;
  auto engine = make_horizon_engine(method, p);
  HorizonField f;
  ProgressCounter progress;
  engine->compute(t, Window::whole(t), f, progress);
  return sky_view_products(t, Window::whole(t), f, engine->radius(), EdgeMode::open);
}

TEST(RealSamples, GothenburgSweepAndMarchAgainstTheRayCastReference) {
  const std::string path = shared_file("city_goteborg/DSM_KRbig.tif");
  REQUIRE_SHARED(path);
  const Terrain t = read_terrain(path, {});
  EXPECT_EQ(t.width(), 234);
  EXPECT_EQ(t.height(), 223);
  const int n = 32;
  const SkyViewProducts ref = products_of(t, "raycast", n);
  const ErrorStats sweep = compare_to_reference(products_of(t, "sweep", n).svf, ref.svf);
  const ErrorStats march = compare_to_reference(products_of(t, "march", n).svf, ref.svf);
  RecordProperty("sweep_p99", std::to_string(sweep.p99));
  RecordProperty("march_p99", std::to_string(march.p99));
  std::printf("Gothenburg, %d directions: sweep p99 %.4f rmse %.4f; march p99 %.4f rmse %.4f\n", n, sweep.p99,
              sweep.rmse, march.p99, march.rmse);
  // Measured: sweep 0.0004 (0.0003 with two far lines, the default until Dec 3),
  // march 0.0000 (both read row and column crossings, where the shared mesh peaks).
  EXPECT_LT(march.p99, 0.002);
  EXPECT_LT(sweep.p99, 0.005);
  EXPECT_LT(std::abs(sweep.bias), 0.002);
  EXPECT_LT(std::abs(march.bias), 0.002);
}

// The bundled synthetic city (sample_dems/, always present): the accuracy targets.
TEST(RealSamples, BundledCitySweepAndMarchAgainstTheRayCastReference) {
  const Terrain t = read_terrain(std::string(SKYVIEW_SOURCE_DIR) + "/sample_dems/city.tif", {});
  const int n = 32;
  const SkyViewProducts ref = products_of(t, "raycast", n);
  const ErrorStats sweep = compare_to_reference(products_of(t, "sweep", n).svf, ref.svf);
  const ErrorStats march = compare_to_reference(products_of(t, "march", n).svf, ref.svf);
  std::printf("city.tif, %d directions: sweep p99 %.4f rmse %.4f; march p99 %.4f rmse %.4f\n", n, sweep.p99, sweep.rmse,
              march.p99, march.rmse);
  // The defaults, 64 near steps and one far line: within the 0.005 with room to spare
  // (measured 0.0036 here; 0.0023 at 16 directions, 0.0028 at 64).
  EXPECT_LT(sweep.p99, 0.0045);
  EXPECT_LT(march.p99, 0.01);
  // Two far lines: slower and closer (measured 0.0021 here).
  const ErrorStats two = compare_to_reference(products_of(t, "sweep", n, 0, 2).svf, ref.svf);
  std::printf("city.tif, %d directions: sweep with two far lines p99 %.4f\n", n, two.p99);
  EXPECT_LT(two.p99, 0.7 * sweep.p99);
}

TEST(RealSamples, SloveneLidarTerrainWithNanNodata) {
  const std::string path = shared_file("terrain/TM1_564_146_nodata.tif");
  REQUIRE_SHARED(path);
  ReadReport report;
  const Terrain t = read_terrain(path, {}, &report);
  EXPECT_GT(report.nodata_cells, 0);
  EXPECT_EQ(report.undeclared_nan_cells, 0) << "the file declares NaN as nodata";
  const SkyViewProducts p = products_of(t, "sweep", 16);
  std::int64_t valid = 0;
  double sum = 0;
  for (int r = 0; r < t.height(); ++r) {
    for (int c = 0; c < t.width(); ++c) {
      const float v = p.svf(c, r);
      ASSERT_EQ(std::isnan(v), !t.valid(c, r)) << c << "," << r;
      if (!t.valid(c, r)) continue;
      ASSERT_GE(v, 0.0f);
      ASSERT_LE(v, 1.0f);
      sum += v;
      ++valid;
    }
  }
  // Rolling lidar terrain (255-325 m over 1 km): mostly open sky.
  EXPECT_GT(sum / valid, 0.85);
  EXPECT_LT(sum / valid, 1.0);
}

TEST(RealSamples, AthensDsmWithDeclaredNodata) {
  const std::string path = shared_file("city_athens/DSM.tif");
  REQUIRE_SHARED(path);
  const Terrain t = read_terrain(path, {});
  EXPECT_TRUE(t.frame.description().find("Greek") != std::string::npos) << t.frame.description();
  const SkyViewProducts sweep = products_of(t, "sweep", 16);
  const SkyViewProducts march = products_of(t, "march", 16);
  const ErrorStats d = compare_to_reference(sweep.svf, march.svf);
  EXPECT_LT(d.p99, 0.03);
  EXPECT_LT(std::abs(d.bias), 0.003);
}

}  // namespace
