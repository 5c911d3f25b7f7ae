// The exposure bench: cells sorted by kind, and errors against the exact reference that vanish
// for the reference's own settings.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/cli_run.h"
#include "core/test_support.h"
#include "exposure_test_support.h"
#include "skyview/benchmark/exposure_benchmark.h"

namespace skyview {
namespace {

// A 10 m block (|e|, |n| <= 5) beside a slope falling north (n > 20) on a 1 m grid.
double scene(double e, double n) {
  if (std::abs(e) <= 5 && std::abs(n) <= 5) return 10.0;
  if (n > 20) return 0.5 * (n - 20);  // rises towards the north: faces south
  return 0.0;
}

double north_facing(double e, double n) {
  if (std::abs(e) <= 5 && std::abs(n) <= 5) return 10.0;
  if (n > 20) return -0.5 * (n - 20);  // falls towards the north
  return 0.0;
}

TEST(ExposureBench, CellsAreSortedByKind) {
  const Terrain t = test::terrain_of(north_facing, 61, 1.0);
  const Grid<unsigned char> kinds = classify_cells(t);
  auto kind = [&](double e, double n) { return CellKind(kinds(30 + static_cast<int>(e), 30 - static_cast<int>(n))); };
  EXPECT_EQ(kind(0, 0), CellKind::roof);
  EXPECT_EQ(kind(6, 0), CellKind::wall_foot);  // beside the block
  EXPECT_EQ(kind(9, 0), CellKind::street);     // level, with the block within 10 m
  EXPECT_EQ(kind(0, 25), CellKind::north_slope);
  EXPECT_EQ(kind(-25, -25), CellKind::other);  // open ground
  const Terrain south = test::terrain_of(scene, 61, 1.0);
  EXPECT_EQ(CellKind(classify_cells(south)(30, 5)), CellKind::other);  // that slope faces south
}

TEST(ExposureBench, TheReferencesOwnSettingsHaveNoError) {
  const Terrain t = test::terrain_of(north_facing, 41, 1.0);
  const ExposureSky sky = test::make_sky(test::clear_sky(50, "2024-06-20T00:00Z", "2024-06-22T00:00Z", "1h"), 128);
  const ExposureBenchReference ref = exposure_bench_reference(t, sky, 16);
  std::vector<ExposureBenchConfig> configs;
  for (const ExposureBenchConfig& c : default_exposure_bench_grid()) {
    if (c.label == "exact sweep d=16" || c.label == "sweep d=8 area") configs.push_back(c);
  }
  ASSERT_EQ(configs.size(), 2u);
  const auto results = run_exposure_bench(t, sky, configs, ref, 1);
  const ExposureBenchResult& fast = results[0].config.method == ExposureMethod::fast ? results[0] : results[1];
  const ExposureBenchResult& exact = &fast == &results[0] ? results[1] : results[0];
  EXPECT_EQ(exact.all.p99, 0.0);
  EXPECT_GT(exact.all.cells, 1000);
  EXPECT_GT(fast.all.p99, 0.0);
  EXPECT_LT(fast.all.p99, 0.5);
  EXPECT_NE(exposure_bench_to_markdown("scene", ref, results).find("| exact sweep d=16 |"), std::string::npos);
}

TEST(ExposureBench, CommandWritesItsFilesAndRefusesSkyOptionsWithoutExposure) {
  const std::string dir = test::temp_dir("exposure-bench");
  GeoReference g;
  g.geotransform = {500000.0, 2.0, 0.0, 6400000.0, 0.0, -2.0};
  g.has_geotransform = true;
  g.crs_wkt = test::wkt_of("EPSG:32633");
  write_terrain(dir + "/dsm.tif", rasterize(north_facing, 21, 21, g), WriteOptions{});
  test::expect_one_line_error(
      test::run_skyview("bench " + dir + "/dsm.tif --out " + dir + "/b --from 2024-06-20T00:00Z", dir),
      "--from applies only to --exposure", 2);
  EXPECT_FALSE(std::filesystem::exists(dir + "/b"));
  const test::RunResult r = test::run_skyview("bench " + dir + "/dsm.tif --exposure --out " + dir +
                                                  "/b --from 2024-06-20T00:00Z --to 2024-06-21T00:00Z --step 2h "
                                                  "--map-size 64 --reference-directions 16 --repeat 1 -q",
                                              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"exposure.json", "exposure.md", "exposure.png"})
    EXPECT_TRUE(std::filesystem::exists(dir + "/b/" + f)) << f;
}

}  // namespace
}  // namespace skyview
