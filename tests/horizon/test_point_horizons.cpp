// Point queries: an observer's horizons along its own rays, against the canyon formula, the march's
// cells and the Embree ray cast.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/test_support.h"
#include "skyview/core/error.h"
#include "skyview/horizon/point_horizons.h"

namespace skyview {
namespace {

using test::kDeg;

PointHorizonOptions options(int directions, const std::string& method = "march") {
  PointHorizonOptions o;
  o.params.directions = directions;
  o.params.curvature = "off";
  o.method = method;
  return o;
}

// Observer at height h, x metres east of the centreline of an infinite canyon of width W and walls
// of height H along north: each wall fills half the azimuths with tan h(φ) = a |sin φ|, a = (H - h)
// / (distance to the wall), whose svf share is cos(atan a) / 2. On the centreline svf = cos(atan(2(H -
// h)/W)).
double canyon_svf(double W, double H, double h, double x) {
  return 0.5 * (std::cos(std::atan((H - h) / (W / 2 - x))) + std::cos(std::atan((H - h) / (W / 2 + x))));
}

TEST(PointHorizons, ObserverInAStreetCanyonSeesTheFormulasSky) {
  const double W = 10.0, H = 20.0;
  // 1 m cells: wall cells at |east| >= 5, so the walls' tops stand at exactly +-5 m.
  const Terrain t = rasterize(street_canyon(W, H), 41, 1601, local_grid(41, 1601, 1.0));
  std::vector<Observer> obs;
  for (double h : {0.01, 1.1, 5.0}) obs.push_back({20.0, 800.0, h});  // the centreline
  obs.push_back({21.37, 800.5, 1.1});                                 // 1.37 m east, between centres
  obs.push_back({18.2, 799.25, 2.0});                                 // 1.8 m west
  for (const std::string method : {"march", "raycast"}) {
    const PointHorizons ph = point_horizons(t, obs, options(360, method));
    for (std::size_t i = 0; i < obs.size(); ++i) {
      ASSERT_TRUE(ph.problem[i].empty()) << ph.problem[i];
      const double x = obs[i].col - 20.0;
      const double expected = canyon_svf(W, H, obs[i].height, x);
      const PointSkyView v = point_sky_view(t, obs[i], ph.of(i), ph.directions, ph.sector_rotation);
      // 360 sectors and walls that end 800 m away: within 0.002 of the infinite canyon.
      EXPECT_NEAR(v.svf, expected, 0.002) << method << " observer " << i;
      EXPECT_NEAR(v.svf_surface, v.svf, 1e-9) << "a flat floor";
    }
    // h = 1.1 on the centreline: cos(atan(2 (20 - 1.1) / 10)) = 0.2556.
    EXPECT_NEAR(canyon_svf(W, H, 1.1, 0.0), 0.2557, 1e-4);
  }
}

TEST(PointHorizons, AtACellCentreOnTheSurfaceTheyAreTheMarchsOwnBitForBit) {
  const Terrain t = rasterize(synthetic_city(3), 121, 121, local_grid(121, 121, 1.0));
  HorizonParams p;
  p.directions = 32;
  p.radius = 1e5;  // beyond the raster: every crossing to its edge
  p.curvature = "off";
  auto march = make_horizon_engine("march", p);
  const std::vector<CellIndex> cells = {{60, 60}, {10, 100}, {0, 0}, {120, 57}, {33, 71}};
  std::vector<Observer> obs;
  for (const CellIndex& c : cells) obs.push_back({double(c.col), double(c.row), 0.0});
  const PointHorizons ph = point_horizons(t, obs, options(32));
  for (std::size_t i = 0; i < cells.size(); ++i) {
    HorizonField f;
    ProgressCounter progress;
    march->compute(t, {cells[i].col, cells[i].row, 1, 1}, f, progress);
    for (int k = 0; k < 32; ++k) EXPECT_EQ(ph.of(i)[k], f.upper_at(0, k)) << "cell " << i << " direction " << k;
  }
}

TEST(PointHorizons, MarchMatchesTheRayCastBetweenCellCentresAboveACity) {
  const Terrain t = rasterize(synthetic_city(5), 151, 151, local_grid(151, 151, 1.0));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(2.0, 148.0), height(0.3, 12.0);
  std::vector<Observer> obs;
  for (int i = 0; i < 20; ++i) obs.push_back({pos(rng), pos(rng), height(rng)});
  const PointHorizons march = point_horizons(t, obs, options(64));
  const PointHorizons cast = point_horizons(t, obs, options(64, "raycast"));
  double worst = 0.0, worst_svf = 0.0;
  int high = 0;
  for (std::size_t i = 0; i < obs.size(); ++i) {
    for (int k = 0; k < 64; ++k) {
      worst = std::max(worst, std::abs(double(march.of(i)[k]) - cast.of(i)[k]));
      high += march.of(i)[k] > 0.1f;
    }
    const double a = point_sky_view(t, obs[i], march.of(i), 64, 0.0).svf;
    const double b = point_sky_view(t, obs[i], cast.of(i), 64, 0.0).svf;
    worst_svf = std::max(worst_svf, std::abs(a - b));
  }
  EXPECT_GT(high, 100) << "the observers must see buildings";
  EXPECT_LT(worst, 2e-4);  // the ray cast brackets to 1e-5 rad; float rays graze corners
  EXPECT_LT(worst_svf, 1e-4);
}

TEST(PointHorizons, BadObserversAreReportedAndTheOthersComputed) {
  Terrain t = rasterize(circular_pit(10.0, 5.0), 41, 41, local_grid(41, 41, 1.0));
  t.heights(5, 5) = NAN;
  const std::vector<Observer> obs = {{20, 20, 1.0}, {-3, 20, 1.0}, {5.2, 5.3, 1.0}, {40.4, 20, 1.0}, {20, 41, 1.0}};
  const PointHorizons ph = point_horizons(t, obs, options(16));
  EXPECT_TRUE(ph.problem[0].empty());
  EXPECT_EQ(ph.problem[1], "outside the raster");
  EXPECT_EQ(ph.problem[2], "on nodata");
  EXPECT_TRUE(ph.problem[3].empty()) << "within the raster's extent, half a cell past the last centre";
  EXPECT_EQ(ph.problem[4], "outside the raster");
  EXPECT_FALSE(std::isnan(ph.of(0)[0]));
  EXPECT_TRUE(std::isnan(ph.of(1)[0]));
  EXPECT_TRUE(std::isnan(ph.of(2)[0]));
  EXPECT_NEAR(ph.eye[0] - ph.ground[0], 1.0, 1e-9);
  EXPECT_THROW(point_horizons(t, {{20, 20, -1.0}}, options(16)), Error);
  EXPECT_THROW(point_horizons(t, obs, options(16, "sweep")), Error);
  EXPECT_THROW(point_horizons(t, {{20, 20, 0.0}}, options(16, "raycast")), Error) << "an eye on the surface";
}

TEST(PointHorizons, RisingStepsEndAtTheHorizon) {
  const Terrain t = rasterize(synthetic_city(2), 101, 101, local_grid(101, 101, 1.0));
  PointHorizonOptions o = options(48);
  o.rising_steps = true;
  const PointHorizons ph = point_horizons(t, {{50.3, 49.6, 1.5}}, o);
  for (int k = 0; k < 48; ++k) {
    const std::vector<RisingStep>& s = ph.rising[0][k];
    ASSERT_FALSE(s.empty());
    for (std::size_t j = 1; j < s.size(); ++j) {
      EXPECT_GT(s[j].distance, s[j - 1].distance);
      EXPECT_GT(s[j].slope, s[j - 1].slope);
    }
    EXPECT_NEAR(std::atan(s.back().slope), ph.of(0)[k], 1e-6);
  }
}

}  // namespace
}  // namespace skyview
