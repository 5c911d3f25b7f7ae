// Error statistics (what `skyview bench` and `skyview compare` report) and the compare command.
#include <sys/wait.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "skyview/sky_view/error_stats.h"
#include "skyview/benchmark/method_benchmark.h"
#include "test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// value = reference + d with d = -0.001 i for i = 0..99, and cells that either side leaves out.
struct KnownErrors {
  Grid<float> value{12, 10}, reference{12, 10};
  KnownErrors() {
    for (int i = 0; i < 100; ++i) {
      reference(i % 10, i / 10) = 0.5f + 0.001f * static_cast<float>(i % 7);
      value(i % 10, i / 10) = reference(i % 10, i / 10) - 0.001f * static_cast<float>(i);
    }
    for (int row = 0; row < 10; ++row) value(10, row) = kNaN, reference(11, row) = kNaN;
  }
};

// The bench's report says each run's true radius (the march's default 500 m, none for the unlimited
// sweep: 0 would read as a zero radius) and marks runs finer than their reference.
TEST(BenchReport, NamesRadiiAndRunsFinerThanTheReference) {
  const Terrain t = rasterize(circular_pit(5.0, 3.0), 15, 15, local_grid(15, 15, 1.0));
  const BenchReference ref = compute_reference(t, 16);
  std::vector<BenchConfig> configs(3);
  configs[0].method = "march", configs[0].params.directions = 16;
  configs[1].method = "march", configs[1].params.directions = 8, configs[1].params.radius = 7.5;
  configs[2].method = "sweep", configs[2].params.directions = 32, configs[2].params.samples = 64;
  configs[2].params.far_lines = 2;
  for (auto& c : configs) c.params.curvature = "off";
  const auto results = run_bench(t, configs, ref, 1, nullptr);
  const nlohmann::json j = bench_to_json("pit.tif", ref, results);
  ASSERT_EQ(j["results"].size(), 3u);
  EXPECT_EQ(j["results"][0]["radius_m"], 500.0);
  EXPECT_EQ(j["results"][1]["radius_m"], 7.5);
  EXPECT_TRUE(j["results"][2]["radius_m"].is_null());
  EXPECT_EQ(j["results"][0]["reference_limited"], false) << "as many directions: the method's own error";
  EXPECT_EQ(j["results"][1]["reference_limited"], false);
  EXPECT_EQ(j["results"][2]["reference_limited"], true);
  EXPECT_LT(j["results"][0]["svf"]["max_abs"].get<double>(), 0.01) << "the march on the reference's surface";
  const std::string md = bench_to_markdown("pit.tif", ref, results);
  EXPECT_NE(md.find("| sweep d=32 near=64 2 lines † |"), std::string::npos) << md;
  EXPECT_EQ(md.find("| march d=16 r=500 † |"), std::string::npos) << md;
  // Beside the reference, the near-continuous svf of 1024 sectors at (here all 225) cells: finer
  // sectors come closer to it.
  EXPECT_EQ(j["continuous_reference"]["sectors"], 1024);
  EXPECT_EQ(j["continuous_reference"]["cells"], 225);
  EXPECT_EQ(j["results"][2]["svf_continuous"]["cells"], 225);
  EXPECT_LT(j["results"][2]["svf_continuous"]["p99_abs"].get<double>(),
            j["results"][1]["svf_continuous"]["p99_abs"].get<double>());
  EXPECT_NE(md.find("cont. p99"), std::string::npos) << md;
}

// The sweep's default grid ends with 16 directions along the grid's lines, named so in the report.
TEST(BenchReport, TheSweepsGridIncludesGridLineDirections) {
  const std::vector<BenchConfig> grid = default_bench_grid({"sweep"});
  ASSERT_FALSE(grid.empty());
  EXPECT_EQ(grid.back().params.spacing, AzimuthSpacing::grid_lines);
  EXPECT_EQ(grid.back().params.directions, 16);
  EXPECT_EQ(grid.back().label(), "sweep d=16 grid lines");
  const Terrain t = rasterize(circular_pit(5.0, 3.0), 15, 15, local_grid(15, 15, 1.0));
  const BenchReference ref = compute_reference(t, 16, AzimuthOrigin::grid);
  std::vector<BenchConfig> configs{grid.back()};
  configs[0].params.azimuth_origin = AzimuthOrigin::grid;
  const nlohmann::json j = bench_to_json("pit.tif", ref, run_bench(t, configs, ref, 1, nullptr));
  EXPECT_EQ(j["results"][0]["azimuths"], "grid-lines");
  // The pit's rim is a circle: every direction sees about the same horizon, whatever its share.
  EXPECT_LT(j["results"][0]["svf_continuous"]["p99_abs"].get<double>(), 0.02);
}

// The front judges by the error against the continuous svf where the bench measured it: against
// the 64-sector ray cast, 256 directions would look no better than 64 (it is their sector error).
TEST(BenchReport, ParetoFrontJudgesByTheContinuousErrorWhereMeasured) {
  auto result = [](double seconds, double raycast_p99, double continuous_p99, std::int64_t continuous_cells) {
    BenchResult r;
    r.seconds = seconds;
    r.svf.p99 = raycast_p99;
    r.svf.cells = 100;
    r.svf_continuous.p99 = continuous_p99;
    r.svf_continuous.cells = continuous_cells;
    return r;
  };
  std::vector<BenchResult> rs = {result(1, 0.001, 0.009, 1000), result(2, 0.009, 0.002, 1000),
                                 result(3, 0.0005, 0.005, 1000)};
  mark_pareto_front(rs);
  EXPECT_TRUE(rs[0].pareto);
  EXPECT_TRUE(rs[1].pareto);
  EXPECT_FALSE(rs[2].pareto);                            // slower than rs[1] and farther from the continuous svf
  for (BenchResult& r : rs) r.svf_continuous.cells = 0;  // not measured: by the ray cast
  mark_pareto_front(rs);
  EXPECT_TRUE(rs[0].pareto);
  EXPECT_FALSE(rs[1].pareto);
  EXPECT_TRUE(rs[2].pareto);
}

TEST(ErrorStats, KnownErrors) {
  const KnownErrors k;
  const ErrorStats e = compare_to_reference(k.value, k.reference, 0.0505);
  EXPECT_EQ(e.cells, 100);
  EXPECT_NEAR(e.bias, -0.0495, 1e-6);                              // mean of -0.001 i
  EXPECT_NEAR(e.rmse, std::sqrt(328350.0 / 100.0) * 0.001, 1e-6);  // sum of i^2 = 328350
  EXPECT_NEAR(e.p99, 0.098, 1e-6);                                 // nearest rank: the 99th of 100
  EXPECT_NEAR(e.max_abs, 0.099, 1e-6);
  EXPECT_DOUBLE_EQ(e.share_above, 0.49);  // i = 51..99
  EXPECT_DOUBLE_EQ(e.threshold, 0.0505);
}

TEST(ErrorStats, NothingInCommon) {
  Grid<float> a(3, 3, kNaN), b(3, 3, 1.0f);
  EXPECT_EQ(compare_to_reference(a, b).cells, 0);
}

struct RunResult {
  int exit_code;
  std::string err;
};

class CompareCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = temp_dir("compare");
    georef = local_grid(12, 10, 1.0);
    write(dir + "/value.tif", k.value);
    write(dir + "/reference.tif", k.reference);
  }
  void write(const std::string& path, const Grid<float>& g, const GeoReference* other = nullptr) const {
    write_bands(path, g.width(), g.height(), other ? *other : georef, {{"svf", "1", g.data(), {}}}, {});
  }
  void write_dem(const std::string& path, const Grid<float>& g) const {
    write_bands(path, g.width(), g.height(), georef, {{"height", "m", g.data(), {}}}, {});
  }
  RunResult run(const std::string& args) const {
    const std::string err_file = dir + "/stderr.txt";
    const int status =
        std::system((std::string(SKYVIEW_EXE) + " compare " + args + " 2>" + err_file + " >/dev/null").c_str());
    std::ifstream in(err_file);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, std::string(std::istreambuf_iterator<char>(in), {})};
  }
  // Statistics of value against reference with `dem` as --dem and --max-slope 5.
  nlohmann::json flat_stats(const Grid<float>& dem) const {
    write_dem(dir + "/dem.tif", dem);
    return stats(dir + "/value.tif " + dir + "/reference.tif --dem " + dir + "/dem.tif --max-slope 5");
  }
  nlohmann::json stats(const std::string& args) const {
    const RunResult r = run(args + " -q --overwrite --json " + dir + "/stats.json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::ifstream in(dir + "/stats.json");
    return nlohmann::json::parse(in);
  }
  KnownErrors k;
  GeoReference georef;
  std::string dir;
};

TEST_F(CompareCli, ReportsTheStatisticsOfTheBands) {
  const nlohmann::json j = stats(dir + "/value.tif " + dir + "/reference.tif --threshold 0.0505");
  EXPECT_EQ(j["cells"], 100);
  EXPECT_NEAR(j["bias"].get<double>(), -0.0495, 1e-6);
  EXPECT_NEAR(j["p99_abs"].get<double>(), 0.098, 1e-6);
  EXPECT_NEAR(j["share_above"].get<double>(), 0.49, 1e-12);
  EXPECT_EQ(j["reference"]["description"], "svf");
}

// Percent against a fraction: value * 0.01 + 0.5 - reference.
TEST_F(CompareCli, ScaleAndOffsetApplyToTheJudgedRaster) {
  Grid<float> percent(12, 10);
  for (std::size_t i = 0; i < percent.size(); ++i) percent.values()[i] = (k.reference.values()[i] - 0.5f) * 100.0f;
  write(dir + "/percent.tif", percent);
  const nlohmann::json j = stats(dir + "/percent.tif " + dir + "/reference.tif --scale 0.01 --offset 0.5");
  EXPECT_EQ(j["cells"], 110);  // column 10 is valid in both now
  EXPECT_LT(j["max_abs"].get<double>(), 1e-6);
}

// A wall one cell thick: with --max-slope, the cells whose Horn slope it raises are left out.
TEST_F(CompareCli, MaxSlopeLeavesOutSteepCells) {
  Grid<float> dem(12, 10, 0.0f);
  for (int row = 0; row < 10; ++row) dem(5, row) = 10.0f;
  const nlohmann::json all = stats(dir + "/value.tif " + dir + "/reference.tif");
  const nlohmann::json flat = flat_stats(dem);
  EXPECT_EQ(all["cells"], 100);
  // Columns 4 and 6 are steep. Along the wall Horn's differences cancel, and at its two end cells
  // the differences along it fall back to one side, which is level too.
  EXPECT_EQ(flat["left_out_steep"], 20);
  EXPECT_EQ(flat["cells"], 80);
}

// Only cells compared can be left out: with the wall on column 10, columns 9 and 11 are steep, but
// column 11 has no reference (until Dec 3 it was counted among the left out, and a pair of rasters
// with nothing in common read "every cell valid in both is steeper").
TEST_F(CompareCli, MaxSlopeCountsOnlyCellsValidInBoth) {
  Grid<float> dem(12, 10, 0.0f);
  for (int row = 0; row < 10; ++row) dem(10, row) = 10.0f;
  const nlohmann::json flat = flat_stats(dem);
  EXPECT_EQ(flat["left_out_steep"], 10);
  EXPECT_EQ(flat["cells"], 90);
  write(dir + "/empty.tif", Grid<float>(12, 10, kNaN));
  const RunResult r = run(dir + "/value.tif " + dir + "/empty.tif --dem " + dir + "/dem.tif --max-slope 5");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("no cell is valid in both"), std::string::npos) << r.err;
}

// A cell without a height in --dem has no slope: it is not known to be flat enough, so it is left
// out and counted apart (until Dec 5 it was kept).
TEST_F(CompareCli, MaxSlopeLeavesOutCellsWithoutADemHeight) {
  Grid<float> dem(12, 10, 0.0f);
  dem(2, 2) = dem(2, 3) = kNaN;
  const nlohmann::json flat = flat_stats(dem);
  EXPECT_EQ(flat["left_out_no_dem_height"], 2);
  EXPECT_EQ(flat["left_out_steep"], 0);
  EXPECT_EQ(flat["cells"], 98);
}

// An infinite value would turn every statistic into inf or NaN: refused with the cell, as svf
// refuses an infinite height (until Dec 5 the run printed "rmse -nan" and exited 0).
TEST_F(CompareCli, InfiniteValuesAreRefused) {
  Grid<float> v = k.value;
  v(3, 4) = std::numeric_limits<float>::infinity();
  write(dir + "/inf.tif", v);
  for (const std::string& args :
       {dir + "/inf.tif " + dir + "/reference.tif", dir + "/reference.tif " + dir + "/inf.tif"}) {
    const RunResult r = run(args);
    EXPECT_EQ(r.exit_code, 1) << args;
    EXPECT_NE(r.err.find("holds an infinite value at cell (3, 4)"), std::string::npos) << r.err;
  }
}

// Bands in different units compare nothing: said, unless --scale or --offset converts them.
TEST_F(CompareCli, BandsInDifferentUnitsAreSaid) {
  write_bands(dir + "/degrees.tif", k.value.width(), k.value.height(), georef,
              {{"openness_positive", "degrees", k.value.data(), {}}}, {});
  const RunResult plain = run(dir + "/degrees.tif " + dir + "/reference.tif");
  EXPECT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_NE(plain.err.find("Warning: the bands' units differ ('degrees' against '1')"), std::string::npos) << plain.err;
  const RunResult scaled = run(dir + "/degrees.tif " + dir + "/reference.tif --scale 0.0111");
  EXPECT_EQ(scaled.exit_code, 0) << scaled.err;
  EXPECT_EQ(scaled.err.find("units differ"), std::string::npos) << scaled.err;
  const RunResult same = run(dir + "/value.tif " + dir + "/reference.tif");
  EXPECT_EQ(same.err.find("units differ"), std::string::npos) << same.err;
}

// The JSON report is an output like any other: an existing one is kept unless --overwrite.
TEST_F(CompareCli, KeepsAnExistingJsonUnlessOverwrite) {
  const std::string json = dir + "/kept.json";
  std::ofstream(json) << "earlier";
  const std::string args = dir + "/value.tif " + dir + "/reference.tif -q --json " + json;
  const RunResult refused = run(args);
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.err.find("exists; use --overwrite"), std::string::npos) << refused.err;
  std::ifstream kept(json);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}), "earlier");
  EXPECT_EQ(run(args + " --overwrite").exit_code, 0);
  std::ifstream replaced(json);
  EXPECT_EQ(nlohmann::json::parse(replaced)["cells"], 100);
}

TEST_F(CompareCli, RefusesRastersOnDifferentGrids) {
  write(dir + "/small.tif", Grid<float>(11, 10, 0.5f));
  RunResult r = run(dir + "/small.tif " + dir + "/reference.tif");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("is 11 x 10 cells but"), std::string::npos) << r.err;
  GeoReference shifted = georef;
  shifted.geotransform[0] += 0.5;
  write(dir + "/shifted.tif", k.value, &shifted);
  r = run(dir + "/shifted.tif " + dir + "/reference.tif");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("not the same geotransform"), std::string::npos) << r.err;
  GeoReference utm = georef, elsewhere = georef;
  utm.crs_wkt = wkt_of("EPSG:32633");
  elsewhere.crs_wkt = wkt_of("EPSG:32634");
  write(dir + "/utm.tif", k.reference, &utm);
  write(dir + "/elsewhere.tif", k.value, &elsewhere);
  r = run(dir + "/elsewhere.tif " + dir + "/utm.tif");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("different CRSs"), std::string::npos) << r.err;
  r = run(dir + "/value.tif " + dir + "/reference.tif --max-slope 5");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--max-slope needs --dem"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  write(dir + "/empty.tif", Grid<float>(12, 10, kNaN));
  r = run(dir + "/empty.tif " + dir + "/reference.tif");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("no cell is valid in both"), std::string::npos) << r.err;
}

}  // namespace
