// The far field of tiled runs at unlimited radius (docs/tiling.md): the max-pooled pyramid bounds
// the surface between cell centres, the march over it never misses a blocker and overstates none
// by more than the bound, and a tiled svf run without --radius stays within the bound of a whole
// unlimited run on the synthetic city and on the real terrain tile.
#include <filesystem>
#include <random>

#include "skyview/tiling/far_field.h"
#include "tiling/tiling_test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

Terrain hills(int w, int h) {
  Terrain t;
  t.heights = Grid<float>(w, h);
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      t.heights(c, r) = static_cast<float>(20 * std::sin(c * 0.07) * std::cos(r * 0.05) + 0.02 * c +
                                           8 * std::exp(-((c - 150.0) * (c - 150.0) + (r - 40.0) * (r - 40.0)) / 50));
  t.full_width = w, t.full_height = h;
  return t;
}

// The far field of the hills' march tests: a 40 m halo on 1 m cells, levels read from 8 cells on.
FarFieldSettings hills_settings() {
  FarFieldSettings s;
  s.halo_m = 40;
  s.cell_m = 1;
  s.diagonal_m = std::sqrt(2.0);
  s.cells_per_level = 8;
  return s;
}

// The surface between cell centres (the mesh the methods read) at pixel (x, y), centres at integers.
double bilinear(const Terrain& t, double x, double y) {
  const int c = std::min(static_cast<int>(x), t.width() - 2), r = std::min(static_cast<int>(y), t.height() - 2);
  const double fx = x - c, fy = y - r;
  return (1 - fy) * ((1 - fx) * t.heights(c, r) + fx * t.heights(c + 1, r)) +
         fy * ((1 - fx) * t.heights(c, r + 1) + fx * t.heights(c + 1, r + 1));
}

// visit(col, row, azimuth) for 300 random cells of a 300 x 220 raster (seeded) and 16 azimuths each.
template <class Visit>
void for_each_sample_ray(unsigned seed, Visit&& visit) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> col(0, 299), row(0, 219);
  for (int n = 0; n < 300; ++n) {
    const int c = col(rng), r = row(rng);
    for (int k = 0; k < 16; ++k) visit(c, r, k * M_PI / 8 + 0.1);
  }
}

TEST(OverviewPyramid, EachCellHoldsTheMaximumOfItsBlockGrownByOneCell) {
  const Terrain t = hills(70, 45);
  const OverviewPyramid p(t, 2);
  ASSERT_EQ(p.first_level(), 2);
  ASSERT_EQ(p.level(2).width(), 18);  // ceil(70 / 4)
  ASSERT_EQ(p.level(2).height(), 12);
  ASSERT_EQ(p.level(p.last_level()).width(), 1);
  for (int l = p.first_level(); l <= p.last_level(); ++l) {
    const int b = 1 << l;
    const Grid<float>& g = p.level(l);
    double relief = 0;
    for (int j = 0; j < g.height(); ++j) {
      for (int i = 0; i < g.width(); ++i) {
        float hi = -INFINITY, lo = INFINITY;
        for (int r = std::max(0, j * b - 1); r <= std::min(t.height() - 1, (j + 1) * b); ++r)
          for (int c = std::max(0, i * b - 1); c <= std::min(t.width() - 1, (i + 1) * b); ++c)
            hi = std::max(hi, t.heights(c, r)), lo = std::min(lo, t.heights(c, r));
        ASSERT_EQ(g(i, j), hi) << "level " << l << " cell " << i << ", " << j;
        relief = std::max(relief, static_cast<double>(hi - lo));
      }
    }
    EXPECT_NEAR(p.relief(l), relief, 1e-4) << "level " << l;
  }
}

// The exact far horizon along a ray beyond `from` metres, on the bilinear surface between cell
// centres (1 m cells), sampled finely: a lower bound of the true one, within the slope's change
// over a step.
double exact_far_tangent(const Terrain& t, double x0, double y0, double z0, double azimuth, double from) {
  double best = -INFINITY;
  const double ux = std::sin(azimuth), uy = -std::cos(azimuth);
  for (double d = from;; d += 0.05) {
    const double x = x0 + ux * d - 0.5, y = y0 + uy * d - 0.5;  // centre-based coordinates
    if (x < 0 || y < 0 || x > t.width() - 1 || y > t.height() - 1) break;
    const double z = bilinear(t, x, y);
    best = std::max(best, (z - z0) / d);
  }
  return best;
}

// The lowest tangent likewise (negative openness).
double exact_low_tangent(const Terrain& t, double x0, double y0, double z0, double azimuth, double from) {
  double lowest = INFINITY;
  const double ux = std::sin(azimuth), uy = -std::cos(azimuth);
  for (double d = from;; d += 0.05) {
    const double x = x0 + ux * d - 0.5, y = y0 + uy * d - 0.5;
    if (x < 0 || y < 0 || x > t.width() - 1 || y > t.height() - 1) break;
    const double z = bilinear(t, x, y);
    lowest = std::min(lowest, (z - z0) / d);
  }
  return lowest;
}

TEST(FarField, MarchIsConservativeAndWithinItsBound) {
  const Terrain t = hills(300, 220);
  const FarFieldSettings s = hills_settings();
  auto p = std::make_shared<OverviewPyramid>(t, 1);
  const double diagonal = std::hypot(300, 220);
  const FarFieldBound bound = far_field_bound(*p, s, diagonal);
  ASSERT_GT(bound.angle, 0.0);
  ASSERT_LT(bound.angle, 0.5);  // a bound that says something
  const FarField far(p, s, Jacobian{1, 0, 0, -1}, 300, 220);
  double worst = 0;
  int rays = 0;
  for_each_sample_ray(7, [&](int c, int r, double az) {
    const double exact = exact_far_tangent(t, c + 0.5, r + 0.5, t.heights(c, r), az, s.halo_m);
    if (!(exact > 0)) return;  // the bound and the bands concern angles above the horizontal
    const double f = far.far_tangent(c + 0.5, r + 0.5, t.heights(c, r), az);
    ASSERT_GE(f, exact - 1e-6) << "cell " << c << ", " << r << " azimuth " << az;
    worst = std::max(worst, std::atan(f) - std::atan(exact));
    ++rays;
  });
  ASSERT_GT(rays, 100);
  EXPECT_LE(worst, bound.angle);
  EXPECT_GT(worst, 0.0);
}

// The lowest angles (negative openness) from the min-pooled levels: never above the exact lowest
// angle beyond H, and within the horizon bound of it.
TEST(FarField, LowestAnglesFromTheMinimaAreConservativeAndWithinTheBound) {
  const Terrain t = hills(300, 220);
  const FarFieldSettings s = hills_settings();
  auto p = std::make_shared<OverviewPyramid>(t, 1, true);
  ASSERT_TRUE(p->has_minima());
  const FarFieldBound bound = far_field_bound(*p, s, std::hypot(300, 220));
  const FarField far(p, s, Jacobian{1, 0, 0, -1}, 300, 220);
  double worst = 0;
  int rays = 0;
  for_each_sample_ray(5, [&](int c, int r, double az) {
    const double exact = exact_low_tangent(t, c + 0.5, r + 0.5, t.heights(c, r), az, s.halo_m);
    if (!std::isfinite(exact)) return;
    const double f = far.far_low_tangent(c + 0.5, r + 0.5, t.heights(c, r), az);
    ASSERT_LE(f, exact + 1e-6) << "cell " << c << ", " << r << " azimuth " << az;
    worst = std::max(worst, std::atan(exact) - std::atan(f));
    ++rays;
  });
  ASSERT_GT(rays, 100);
  EXPECT_LE(worst, bound.horizon);
  EXPECT_GT(worst, 0.0);
}

// skyview horizon writes angles of either sign: below the horizontal the far field may also err
// low (a block's entry is nearer than its points), still within FarFieldBound::horizon.
TEST(FarField, MarchIsWithinTheHorizonBoundBelowTheHorizontalToo) {
  const Terrain t = hills(300, 220);
  const FarFieldSettings s = hills_settings();
  auto p = std::make_shared<OverviewPyramid>(t, 1);
  const FarFieldBound bound = far_field_bound(*p, s, std::hypot(300, 220));
  ASSERT_GE(bound.horizon, bound.angle);
  ASSERT_LT(bound.horizon, 0.5);
  const FarField far(p, s, Jacobian{1, 0, 0, -1}, 300, 220);
  double worst = 0;
  int below = 0;
  for_each_sample_ray(11, [&](int c, int r, double az) {
    const double exact = exact_far_tangent(t, c + 0.5, r + 0.5, t.heights(c, r), az, s.halo_m);
    if (!std::isfinite(exact)) return;
    const double f = far.far_tangent(c + 0.5, r + 0.5, t.heights(c, r), az);
    worst = std::max(worst, std::abs(std::atan(f) - std::atan(exact)));
    below += exact < 0;
  });
  ASSERT_GT(below, 100);  // the case this test is about
  EXPECT_LE(worst, bound.horizon);
}

void expect_within_bound(const std::string& dsm, const std::string& dir, const std::string& common, int tile,
                         double max_error) {
  const std::string out = whole_and_tiled("svf", dsm, dir, common, tile, max_error);
  const double halo = std::stod(metadata_item(out, "FAR_FIELD_HALO_M"));
  const double bound_svf = std::stod(metadata_item(out, "FAR_FIELD_BOUND_SVF"));
  const double bound_vis = std::stod(metadata_item(out, "FAR_FIELD_BOUND_SKY_VISIBILITY"));
  const double bound_deg = std::stod(metadata_item(out, "FAR_FIELD_BOUND_ANGLE_DEG"));
  EXPECT_LE(bound_svf, max_error);
  EXPECT_GT(std::stoi(metadata_item(out, "TILES")), 1);
  const double svf = max_difference(out, dir + "/whole.tif", 1);
  const double vis = max_difference(out, dir + "/whole.tif", 2);
  const double openness = max_difference(out, dir + "/whole.tif", 3);
  std::printf(
      "halo %.1f m: svf max error %.5f (bound %.5f), sky_visibility %.5f (bound %.5f), openness_positive "
      "%.3f deg (bound %.3f)\n",
      halo, svf, bound_svf, vis, bound_vis, openness, bound_deg);
  // Within the bound, less float rounding (the near field marches where the whole run sweeps).
  EXPECT_LE(svf, bound_svf + 1e-5);
  EXPECT_LE(vis, bound_vis + 1e-5);
  EXPECT_LE(openness, bound_deg + 1e-3);
  EXPECT_LT(halo, std::hypot(read_band(dsm, 1).values.width(), read_band(dsm, 1).values.height()));
  EXPECT_GT(svf, 0.0);  // the far field is an approximation: a run that equals the whole one tests nothing
}

// The whole runs compared against are the sweep at unlimited radius with every crossing exact
// (--samples at least the raster's size), so that what differs is the far field alone.
TEST(FarField, TiledSvfWithoutRadiusIsWithinTheBoundOnTheCity) {
  const std::string dir = temp_dir("far-field-city");
  const std::string dsm = write_small_city(dir, 240, 200);
  // A 107 m tower over ground at about 0 m: the bound needs H of about twice the relief for 0.2.
  expect_within_bound(dsm, dir, " --products svf,sky_visibility,openness_positive --samples 400", 64, 0.2);
}

TEST(FarField, TiledSvfWithoutRadiusIsWithinTheBoundOnRealTerrain) {
  const std::string dem = real_terrain();
  if (!std::filesystem::exists(dem)) GTEST_SKIP() << "sample data absent: " << dem;
  const std::string dir = temp_dir("far-field-terrain");
  expect_within_bound(dem, dir, " --products svf,sky_visibility,openness_positive --samples 1500", 256, 0.05);
}

// openness_negative's lowest angles beyond the halo come from the pyramid's minima: the band is
// within the horizon angle bound of a whole unlimited run's.
void expect_openness_negative_within_bound(const std::string& dsm, const std::string& dir, const std::string& common,
                                           int tile, double max_error, double sensible) {
  const std::string out = whole_and_tiled("svf", dsm, dir, " --products openness_negative" + common, tile, max_error);
  EXPECT_NE(metadata_item(out, "FAR_FIELD_OPENNESS_NEGATIVE").find("min-pooled"), std::string::npos);
  const double bound = std::stod(metadata_item(out, "FAR_FIELD_BOUND_HORIZON_DEG"));
  const double error = max_difference(out, dir + "/whole.tif", 1);
  std::printf("openness_negative max error %.3f deg (bound %.3f)\n", error, bound);
  EXPECT_LE(error, bound + 1e-3);
  EXPECT_LT(bound, sensible);
  EXPECT_GT(error, 0.0);
}

TEST(FarField, TiledOpennessNegativeIsWithinTheBoundOnTheCity) {
  const std::string dir = temp_dir("far-field-neg-city");
  const std::string dsm = write_small_city(dir, 240, 200);
  expect_openness_negative_within_bound(dsm, dir, " --samples 400", 64, 0.2, 30.0);
}

TEST(FarField, TiledOpennessNegativeIsWithinTheBoundOnRealTerrain) {
  const std::string dem = real_terrain();
  if (!std::filesystem::exists(dem)) GTEST_SKIP() << "sample data absent: " << dem;
  const std::string dir = temp_dir("far-field-neg-terrain");
  expect_openness_negative_within_bound(dem, dir, " --samples 1500", 256, 0.05, 8.0);
}

TEST(FarField, MaxErrorSetsTheBoundAndTheOptionIsRefusedWithoutAFarField) {
  const std::string dir = temp_dir("far-field-options");
  const std::string dsm = write_small_city(dir, 240, 200);
  const RunResult r = run_skyview("svf " + dsm + " " + dir + "/m.tif --tile-size 64 --max-error 0.3", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(metadata_item(dir + "/m.tif", "FAR_FIELD_ERROR_ASKED"), "0.3 (asked)");
  EXPECT_LE(std::stod(metadata_item(dir + "/m.tif", "FAR_FIELD_BOUND_SVF")), 0.3);
  EXPECT_LT(std::stod(metadata_item(dir + "/m.tif", "FAR_FIELD_HALO_M")), 300.0);  // a far field, not the whole raster
  expect_one_line_error(
      run_skyview("svf " + dsm + " " + dir + "/a.tif --radius 9 --tile-size 16 --far-field-error 0.1", dir),
      "--far-field-error applies to tiled runs without --radius", 2);
  expect_one_line_error(run_skyview("svf " + dsm + " " + dir + "/b.tif --far-field-error 0.1", dir),
                        "--far-field-error applies to tiled runs without --radius", 2);
  expect_one_line_error(run_skyview("svf " + dsm + " " + dir + "/c.tif --tile-size 16 --far-field-error 0", dir),
                        "--far-field-error", 2);
  for (const char* name : {"/a.tif", "/b.tif", "/c.tif"}) EXPECT_FALSE(std::filesystem::exists(dir + name)) << name;
}

}  // namespace
