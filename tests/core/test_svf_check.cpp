// The svf check: exact svf at a sample of cells, and how well it predicts the whole raster's error.
#include <set>
#include <utility>

#include "skyview/sky_view/accuracy_choice.h"
#include "skyview/core/error.h"
#include "skyview/sky_view/svf_check.h"
#include "test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

Terrain city(int cols, int rows) { return rasterize(synthetic_city(3), cols, rows, local_grid(cols, rows, 1.0)); }

// The svf of every cell from `method` at 64 directions, without curvature.
Grid<float> svf_of(const Terrain& t, const std::string& name, int near_steps = 0) {
  HorizonParams p;
  p.directions = 64;
  p.curvature = "off";
  p.samples = near_steps;
  p.rays = 0;
  const std::string method = engine_method(name, p);
  auto engine = make_horizon_engine(method, p);
  HorizonField field;
  ProgressCounter progress;
  engine->compute(t, Window::whole(t), field, progress);
  return sky_view_products(t, Window::whole(t), field, engine->radius(), EdgeMode::open).svf;
}

TEST(SvfCheck, QuantileBoundIsTheBinomialOrderStatistic) {
  // Exact binomial sums (Python's fractions): P(Bin(1000, 0.99) <= 995) >= 0.95 first at 995.
  EXPECT_EQ(quantile_upper_rank(1000, 0.99, 0.95), 996);
  EXPECT_EQ(quantile_upper_rank(300, 0.99, 0.95), 300);
  EXPECT_EQ(quantile_upper_rank(10, 0.5, 0.95), 9);
  // 100 samples cannot bound a p99: even their largest is below it with probability 0.37.
  EXPECT_EQ(quantile_upper_rank(100, 0.99, 0.95), 0);
  EXPECT_EQ(quantile_upper_rank(0, 0.99, 0.95), 0);
}

TEST(SvfCheck, SamplesDistinctValidCellsTheSameEachTime) {
  Terrain t = city(81, 71);
  for (int r = 20; r < 40; ++r) {
    for (int c = 10; c < 50; ++c) t.heights(c, r) = NAN;
  }
  SvfCheckOptions o;
  o.cells = 300;
  o.directions = 8;
  const SvfCheck a(t, o), b(t, o);
  ASSERT_EQ(a.cells().size(), 300u);
  EXPECT_FALSE(a.exhaustive());
  std::set<std::pair<int, int>> seen;
  for (const CellIndex& c : a.cells()) {
    EXPECT_TRUE(t.valid(c.col, c.row)) << c.col << " " << c.row;
    seen.insert({c.col, c.row});
  }
  EXPECT_EQ(seen.size(), 300u);
  for (std::size_t i = 0; i < a.cells().size(); ++i) {
    EXPECT_EQ(a.cells()[i].col, b.cells()[i].col);
    EXPECT_EQ(a.cells()[i].row, b.cells()[i].row);
    EXPECT_EQ(a.reference()[i], b.reference()[i]);
  }
  // The sample spreads over the raster: a fifth of it in each band of rows, within sampling noise.
  int top = 0;
  for (const CellIndex& c : a.cells()) top += c.row < 14;
  EXPECT_GT(top, 35);
  EXPECT_LT(top, 85);
  o.seed = 2;
  const SvfCheck other(t, o);
  int same = 0;
  for (const CellIndex& c : other.cells()) same += seen.count({c.col, c.row}) > 0;
  EXPECT_LT(same, 150);
  o.cells = 100000;
  const SvfCheck all(t, o);
  EXPECT_TRUE(all.exhaustive());
  EXPECT_EQ(all.cells().size(), 81u * 71u - 20u * 40u);
  o.cells = 0;
  EXPECT_THROW(SvfCheck(t, o), Error);
}

TEST(SvfCheck, ReferenceIsOneOnAPlaneAndTheRayCastsSvfOnACity) {
  const Terrain flat = rasterize([](double, double) { return 3.0; }, 41, 41, local_grid(41, 41, 1.0));
  SvfCheckOptions o;
  o.cells = 50;
  const SvfCheck plane(flat, o);
  for (double v : plane.reference()) EXPECT_EQ(v, 1.0);
  EXPECT_EQ(plane.sector_p99(), 0.0);

  const Terrain t = city(101, 91);
  o.cells = 400;
  const SvfCheck check(t, o);
  const SvfCheckResult r = check.measure(svf_of(t, "raycast"));
  EXPECT_EQ(r.error.cells, 400);
  // Both are exact on one surface, the ray cast to its 1e-5 rad bracket (measured 1.8e-7).
  EXPECT_LT(r.error.max_abs, 1e-5);
  // A 64-sector svf is far from the continuous one in a city (measured 0.0132 against 256
  // sectors): the check says how far.
  EXPECT_GT(check.sector_p99(), 0.008);
  EXPECT_LT(check.sector_p99(), 0.02);
  EXPECT_NEAR(r.error_fine.p99, check.sector_p99(), 1e-5);
}

TEST(SvfCheck, FourTimesTheSectorsHoldTheReferencesOwn) {
  const Terrain t = city(61, 61);
  SvfCheckOptions o;
  o.cells = 200;
  o.directions = 16;
  const SvfCheck coarse(t, o);
  o.directions = 64;
  const SvfCheck fine(t, o);
  ASSERT_EQ(coarse.fine_directions(), 64);
  ASSERT_EQ(coarse.cells().size(), fine.cells().size());
  for (std::size_t i = 0; i < fine.cells().size(); ++i) {
    EXPECT_EQ(coarse.cells()[i].col, fine.cells()[i].col);
    EXPECT_EQ(coarse.fine_reference()[i], fine.reference()[i]);  // the same 64 horizons, bit for bit
  }
}

TEST(SvfCheck, MeasuresErrorsAsGiven) {
  const Terrain t = city(61, 61);
  SvfCheckOptions o;
  o.cells = 500;
  o.directions = 16;
  const SvfCheck check(t, o);
  Grid<float> svf(t.width(), t.height(), NAN);
  for (std::size_t i = 0; i < check.cells().size(); ++i) {
    const CellIndex c = check.cells()[i];
    svf(c.col, c.row) = static_cast<float>(check.reference()[i] + (i % 100 == 7 ? -0.05 : 0.01));
  }
  svf(check.cells()[3].col, check.cells()[3].row) = NAN;  // a cell the run left nodata is left out
  const SvfCheckResult r = check.measure(svf);
  EXPECT_EQ(r.error.cells, 499);
  EXPECT_NEAR(r.error.max_abs, 0.05, 1e-6);
  EXPECT_NEAR(r.error.p99, 0.05, 1e-6);  // 5 of 499 cells (1%) are off by 0.05
  EXPECT_NEAR(r.error.bias, (494 * 0.01 - 5 * 0.05) / 499, 1e-6);
  EXPECT_NEAR(r.p99_upper95, 0.05, 1e-6);
  // The error against the four-times-finer sectors (what --max-error is held to) and its bound
  // come the same way, from the finer reference.
  for (std::size_t i = 0; i < check.cells().size(); ++i) {
    const CellIndex c = check.cells()[i];
    if (i != 3) svf(c.col, c.row) = static_cast<float>(check.fine_reference()[i] + (i % 100 == 7 ? 0.04 : -0.01));
  }
  const SvfCheckResult f = check.measure(svf);
  EXPECT_NEAR(f.error_fine.p99, 0.04, 1e-6);
  EXPECT_NEAR(f.fine_p99_upper95, 0.04, 1e-6);
  EXPECT_NEAR(f.error_fine.bias, (494 * -0.01 + 5 * 0.04) / 499, 1e-6);
}

TEST(SvfCheck, ASampleOfCellsPredictsTheWholeRastersError) {
  const Terrain t = city(121, 111);
  const Grid<float> reference = svf_of(t, "raycast");
  // A cheap sweep (8 near steps, one far line) errs in the city by about 0.01 at p99.
  const Grid<float> svf = svf_of(t, "sweep", 8);
  const ErrorStats whole = compare_to_reference(svf, reference);
  ASSERT_GT(whole.p99, 0.005);
  SvfCheckOptions o;
  o.cells = 1000;
  const SvfCheckResult sampled = SvfCheck(t, o).measure(svf);
  // Measured: 0.01390 (bound 0.01546) from 1000 of 13431 cells, where all give 0.01398.
  EXPECT_NEAR(sampled.error.p99, whole.p99, 0.15 * whole.p99);
  EXPECT_GE(sampled.p99_upper95, whole.p99);
  EXPECT_NEAR(sampled.error.bias, whole.bias, 0.001);
  o.cells = 1 << 20;
  const SvfCheckResult all = SvfCheck(t, o).measure(svf);
  EXPECT_TRUE(all.exhaustive);
  EXPECT_EQ(all.error.cells, whole.cells);
  EXPECT_NEAR(all.error.p99, whole.p99, 2e-4);
  EXPECT_EQ(all.p99_upper95, all.error.p99);
  EXPECT_EQ(all.fine_p99_upper95, all.error_fine.p99);
}

TEST(AccuracyChoice, AfterAMeasurementAFinerChoiceScaledByHowFarTheRasterExceeded) {
  HorizonParams base;
  const AccuracyChoice first = choose_for_max_error(0.01, base);
  // Met: nothing more to do.
  EXPECT_FALSE(choose_after_measurement(0.01, first.entry, 0.009, base));
  const double measured = 2.0 * first.entry.worst_p99;
  const auto next = choose_after_measurement(0.01, first.entry, measured, base);
  ASSERT_TRUE(next);
  EXPECT_LT(next->entry.worst_p99, first.entry.worst_p99);
  EXPECT_LE(next->entry.worst_p99, 0.01 * first.entry.worst_p99 / measured);
  EXPECT_EQ(next->params.directions, next->entry.directions);
  // Already the most accurate: none.
  const CalibrationEntry* best = &calibration_table().front();
  for (const CalibrationEntry& e : calibration_table()) {
    if (e.worst_p99 < best->worst_p99) best = &e;
  }
  EXPECT_FALSE(choose_after_measurement(0.0001, *best, 0.01, base));
  // Far off: the most accurate there is.
  const auto last = choose_after_measurement(0.01, first.entry, 1.0, base);
  ASSERT_TRUE(last);
  EXPECT_EQ(last->entry.worst_p99, best->worst_p99);
}

}  // namespace
