// The shadow benchmark shared by bench/bench_shadows and skyview bench --shadows: on a box on a
// plane, exact rays judge themselves perfect, a coarse map's errors are counted as shadow_error
// counts them, and the table carries one row per run.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "core/cli_run.h"
#include "render_test_support.h"
#include "skyview/benchmark/shadow_benchmark.h"
#include "temp_dir.h"

using namespace skyview;
using namespace skyview::test;

TEST(ShadowBench, ExactIsItsOwnReferenceAndAMapIsJudgedByShadowError) {
  Scene s;
  s.meshes.push_back(ground_mesh(100));
  s.meshes.push_back(box_mesh("box", {-5, -5, 0}, {5, 5, 20}));
  const auto scene = std::make_shared<const Scene>(s);
  const ShadowBenchView v = make_shadow_bench_view("box", scene);
  ASSERT_GT(v.receivers.points.size(), 50000u);  // most of the 400 x 300 rays hit the plane
  const ShadowBenchRow exact = run_shadow_bench(v, ShadowMethod::exact, 1);
  EXPECT_EQ(exact.error.wrong, 0u);
  EXPECT_EQ(exact.error.receivers, v.receivers.points.size());
  const ShadowBenchRow pcf = run_shadow_bench(v, ShadowMethod::pcf, 2);
  ShadowOptions o;
  o.eye = v.eye;
  const ShadowError e = shadow_error(*v.rays, shadow_bench_sun(), v.receivers, v.exact, pcf.result, o);
  EXPECT_EQ(pcf.error.wrong, e.wrong);
  EXPECT_EQ(pcf.error.leaks + pcf.error.acne, pcf.error.wrong);
  EXPECT_LT(pcf.error.wrong_share(), 0.01);
  EXPECT_GT(pcf.result.map_bytes, 0u);
  const std::string md = shadow_bench_markdown({exact, pcf});
  EXPECT_NE(md.find("| box | exact | "), std::string::npos);
  EXPECT_NE(md.find("| box | pcf | "), std::string::npos);
  EXPECT_EQ(shadow_bench_json({exact, pcf}).size(), 2u);
}

TEST(ShadowBench, CommandRefusesOptionsOfTheOtherBenches) {
  const std::string dir = temp_dir("shadow-bench");
  expect_one_line_error(run_skyview("bench --shadows --methods march --out " + dir + "/o", dir),
                        "--methods applies only to", 2);
  expect_one_line_error(run_skyview("bench --shadows --exposure --out " + dir + "/o", dir),
                        "--exposure applies only to", 2);
  expect_one_line_error(run_skyview("bench --out " + dir + "/o", dir), "bench needs INPUT", 2);
}
