// The direction set may start on grid north instead of true north (AzimuthOrigin::grid): the
// sectors at multiples of 45° then run along rows, columns and diagonals, where the sweep pushes
// each cell onto its own line's hull. These hold the rotation to the projection's meridian
// convergence, the sweep's exact path to the march, and the products to the rotated sectors.
#include <GeographicLib/TransverseMercator.hpp>

#include <random>

#include "test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

// UTM zone 33N about 200 km west of its central meridian (15° E) near 57.7° N, where grid north
// is about 2.8° off true north.
constexpr double kEasting = 300000.0, kNorthing = 6400000.0;

GeoReference utm_off_meridian(int cols, int rows, double cell) {
  GeoReference g = local_grid(cols, rows, cell);
  g.geotransform[0] += kEasting;
  g.geotransform[3] += kNorthing;
  g.crs_wkt = wkt_of("EPSG:32633");
  return g;
}

HorizonField run(const Terrain& t, const std::string& method, HorizonParams p) {
  auto engine = make_horizon_engine(method, p);
  HorizonField field;
  ProgressCounter progress;
  engine->compute(t, Window::whole(t), field, progress);
  return field;
}

}  // namespace

TEST(AzimuthOrigin, GridTurnsTheSetByTheMeridianConvergence) {
  const int n = 201;
  const Terrain t = rasterize(synthetic_city(3), n, n, utm_off_meridian(n, n, 1.0));
  // GeographicLib's convergence: the bearing of grid north, clockwise from true north.
  const GeoReference& g = t.georef;
  const double x = g.geotransform[0] + 0.5 * n * g.geotransform[1];
  const double y = g.geotransform[3] + 0.5 * n * g.geotransform[5];
  double lat, lon, gamma, scale;
  GeographicLib::TransverseMercator::UTM().Reverse(15.0, x - 500000.0, y, lat, lon, gamma, scale);
  ASSERT_LT(gamma, -2.0) << "the test needs grid north well off true north";
  const double rotation = direction_set_rotation(AzimuthOrigin::grid, t) * 180.0 / M_PI;
  EXPECT_NEAR(rotation, gamma, 1e-4) << "degrees";
  EXPECT_EQ(direction_set_rotation(AzimuthOrigin::north, t), 0.0);

  HorizonParams p;
  p.directions = 8;
  p.azimuth_origin = AzimuthOrigin::grid;
  const HorizonField field = run(t, "sweep", p);
  EXPECT_NEAR(field.sector_rotation * 180.0 / M_PI, gamma, 1e-4);
  EXPECT_NEAR(field.azimuth(0, 2) * 180.0 / M_PI, 90.0 + gamma, 1e-4);
}

// A grid turned clockwise from north (an affine geotransform in metres: one Jacobian everywhere).
GeoReference turned_grid(int cols, int rows, double degrees) {
  const double turn = degrees * M_PI / 180.0;
  GeoReference g = local_grid(cols, rows, 1.0);
  g.geotransform[1] = std::cos(turn), g.geotransform[2] = -std::sin(turn);
  g.geotransform[4] = -std::sin(turn), g.geotransform[5] = -std::cos(turn);
  return g;
}

// A grid turned by 20° from north, where the march and the ray cast step along the very same
// azimuths as the sweep. On the grid's axes and diagonals a cell's ray is its line: the sweep's
// horizons are the exact march's to float rounding, lowest angles, Earth curvature and nodata
// included. (The march's diagonal steps land 1e-16 off the cell centres; until its sampler took
// such points as on the grid line, a nodata neighbour weighted by 1e-16 dropped them, 0.08 rad
// here. Not on a projected CRS: there the march's rays follow each cell's own grid convergence, a
// hair off the raster centre's, which along a wall moves a horizon by 1e-3.)
TEST(AzimuthOrigin, OnGridAxesAndDiagonalsTheSweepIsTheMarch) {
  Terrain t = rasterize(synthetic_city(3), 161, 141, turned_grid(161, 141, 20.0));
  for (int r = 60; r < 70; ++r) t.heights(40, r) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NEAR(direction_set_rotation(AzimuthOrigin::grid, t), 20.0 * M_PI / 180.0, 1e-12);
  HorizonParams p;
  p.directions = 8;
  p.lower = true;
  p.curvature = "on";
  p.azimuth_origin = AzimuthOrigin::grid;
  p.samples = 1;  // a near field would hide a wrong far field; the exact path has none
  const HorizonField sweep = run(t, "sweep", p);
  p.samples = 0;
  p.radius = 1e6;
  const FieldDifference d = field_difference(sweep, run(t, "march", p));
  EXPECT_EQ(d.nan_mismatches, 0u);
  EXPECT_LT(d.worst, 1e-5) << "radians";
  EXPECT_GT(d.high, sweep.upper.size() / 10);
  // The ray cast turns its set too: its own search on the same surface agrees (measured 4.7e-4 rad
  // at worst, where rays graze corners), and 20 degrees away from it does not. Beside the hole too:
  // a ray along a grid line meets the hole's rim on an edge that only one triangle holds, whose hit
  // Embree loses without the skirt hung there (0.36 rad at one cell).
  p.curvature = "off";  // the ray cast has none
  p.rays = 0;
  const HorizonField march = run(t, "march", p);
  EXPECT_LT(field_difference(run(t, "raycast", p), march).worst, 1e-3) << "radians";
  p.azimuth_origin = AzimuthOrigin::north;
  EXPECT_GT(field_difference(run(t, "raycast", p), march).worst, 0.1) << "radians";
}

// The products read each sector at its true azimuth: on a tilted surface (whose own horizon and
// share of the sky depend on a sector's azimuth against its aspect) a rotated set's svf_surface is
// the formula's at that rotation, over the whole field and through the sums direction by direction.
TEST(AzimuthOrigin, TheProductsTurnTheSectorsWithTheSet) {
  const int n = 21, directions = 16;
  const double beta = 30.0 * M_PI / 180.0, aspect = 0.7, rotation = 0.4;
  const Terrain t = rasterize(tilted_plane(beta, aspect), n, n, local_grid(n, n, 1.0));
  HorizonField field;
  field.resize(n, n, directions, false);
  field.sector_rotation = rotation;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.3, 1.2);
  for (float& h : field.upper) h = static_cast<float>(u(rng));
  const Window w = Window::whole(t);
  const SkyViewProducts whole = sky_view_products(t, w, field, INFINITY, EdgeMode::open);
  SkyViewSums sums(t, w, directions);
  for (int k = 0; k < directions; ++k) sums.add(k, 1, field.upper_plane(k), nullptr, field);
  const SkyViewProducts summed = sums.finish(INFINITY, EdgeMode::open);
  std::size_t turned = 0;
  std::vector<float> h(directions);
  for (int r = 1; r < n - 1; ++r) {
    for (int c = 1; c < n - 1; ++c) {
      for (int k = 0; k < directions; ++k) h[k] = field.upper_at(field.cell(c, r), k);
      const double expected = svf_tilted(h.data(), directions, rotation, beta, aspect);
      ASSERT_NEAR(whole.svf_surface(c, r), expected, 1e-5) << c << "," << r;
      ASSERT_NEAR(summed.svf_surface(c, r), expected, 1e-5) << c << "," << r;
      turned += std::abs(svf_tilted(h.data(), directions, 0.0, beta, aspect) - expected) > 1e-3;
    }
  }
  EXPECT_GT(turned, (n - 2) * (n - 2) / 2) << "the rotation must matter for the test to tell";
}

// The same physically: a plane tilted 30° on a grid turned 20° from north, its sectors started on
// grid north. Each cell's horizons are the plane's own, so svf_surface is (1 + cos β) / 2 only
// where the sums take every sector at its true azimuth (dropping the rotation, or turning it the
// wrong way, puts the plane's horizons 20° or 40° away from where the sums look for them).
TEST(AzimuthOrigin, ATiltedPlaneOnATurnedGridSeesHalfTheSky) {
  const int n = 81;
  const double beta = 30.0 * M_PI / 180.0;
  const Terrain t = rasterize(tilted_plane(beta, 0.7), n, n, turned_grid(n, n, 20.0));
  HorizonParams p;
  p.directions = 32;  // summed direction by direction, as skyview svf does
  p.lower = true;
  p.azimuth_origin = AzimuthOrigin::grid;
  const auto engine = make_horizon_engine("sweep", p);
  ProgressCounter progress;
  const Window inner{20, 20, 41, 41};
  const SkyViewProducts out = compute_sky_view(*engine, t, inner, EdgeMode::open, progress);
  for (int r = 0; r < inner.rows; r += 5) {
    for (int c = 0; c < inner.cols; c += 5)
      ASSERT_NEAR(out.svf_surface(c, r), 0.5 * (1.0 + std::cos(beta)), 2e-3) << c << "," << r;
  }
}
