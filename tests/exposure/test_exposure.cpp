// compute_exposure against analytic cases: an open plane receives the map's horizontal integral, a
// canyon floor its svf's share of an isotropic sky, a pit the sun never looks into no beam, and a
// street cell north of a wall the beam an independent step-by-step integral gives.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "exposure_test_support.h"
#include "skyview/core/error.h"

namespace skyview {
namespace {

using test::kDegree;

TEST(Exposure, OpenPlaneReceivesTheMapsHorizontalIntegral) {
  const ExposureSky sky = test::make_sky(test::clear_sky(45, "2024-03-18T00:00Z", "2024-03-22T00:00Z", "1h"), 128);
  const double direct = sky.map.irradiation(ExposureBand::direct, {0, 0, 1}) / 1000;
  const double global = sky.map.irradiation(ExposureBand::global, {0, 0, 1}) / 1000;
  const Terrain flat = test::terrain_of([](double, double) { return 12.0; }, 15, 2.0);
  for (const ExposureMethod method : {ExposureMethod::fast, ExposureMethod::exact}) {
    SCOPED_TRACE(exposure_method_name(method));
    const ExposureBands b = test::run_exposure(flat, sky, method, 16);
    for (const auto& [col, row] : {std::pair{7, 7}, std::pair{0, 0}, std::pair{14, 3}}) {
      EXPECT_NEAR(b.total(col, row), global, 0.005 * global);
      EXPECT_NEAR(b.horizontal_total(col, row), global, 0.005 * global);
      EXPECT_NEAR(b.direct(col, row), direct, 0.005 * global);
      EXPECT_FLOAT_EQ(b.svf(col, row), 1.0f);
      EXPECT_NEAR(b.reflected(col, row), 0.0, 1e-6 * global);
    }
  }
}

TEST(Exposure, CanyonFloorSeesItsSvfShareOfAnIsotropicSky) {
  const ExposureSky sky =
      test::make_sky(test::clear_sky(30, "2024-06-20T00:00Z", "2024-06-22T00:00Z", "1h", "isotropic"), 256);
  const double diffuse_h = sky.map.irradiation(ExposureBand::diffuse, {0, 0, 1}) / 1000;
  // Street 20 m wide between 20 m walls running north: svf at the centre line cos(atan(2H/W)).
  const Terrain canyon = test::terrain_of(street_canyon(20.0, 20.0), 101, 1.0);
  for (const ExposureMethod method : {ExposureMethod::fast, ExposureMethod::exact}) {
    SCOPED_TRACE(exposure_method_name(method));
    const ExposureBands b = test::run_exposure(canyon, sky, method, 64);
    const double svf = b.svf(50, 50);
    EXPECT_NEAR(svf, std::cos(std::atan(2.0)), 0.01);
    EXPECT_NEAR(b.diffuse(50, 50), svf * diffuse_h, 0.01 * svf * diffuse_h);
    // The walls send back albedo × global horizontal over the part of the view that is not sky.
    EXPECT_NEAR(b.reflected(50, 50), 0.2 * b.global_horizontal / 1000 * (1 - svf), 1e-3 * diffuse_h);
  }
}

TEST(Exposure, PitTheSunNeverClearsGetsNoBeamAndThePitFormulaSky) {
  // 60° N in mid-December: the sun stays below 7°; the rim stands 20° above the pit's centre.
  const ExposureSky sky =
      test::make_sky(test::clear_sky(60, "2024-12-15T00:00Z", "2024-12-18T00:00Z", "30m", "isotropic"), 256);
  ASSERT_FALSE(sky.sun.empty());
  for (const SunStep& s : sky.sun) ASSERT_LT(s.elevation, 7 * kDegree);
  const double diffuse_h = sky.map.irradiation(ExposureBand::diffuse, {0, 0, 1}) / 1000;
  const double radius = 30.0, depth = radius * std::tan(20 * kDegree);
  const Terrain pit = test::terrain_of(circular_pit(radius, depth), 81, 1.0);
  const double svf = std::pow(std::cos(20 * kDegree), 2);
  for (const ExposureMethod method : {ExposureMethod::fast, ExposureMethod::exact}) {
    SCOPED_TRACE(exposure_method_name(method));
    const ExposureBands b = test::run_exposure(pit, sky, method, 32);
    EXPECT_EQ(b.direct(40, 40), 0.0f);
    EXPECT_NEAR(b.diffuse(40, 40), svf * diffuse_h, 0.01 * svf * diffuse_h);
    // Outside the pit the plane sees the low sun.
    EXPECT_GT(b.direct(2, 2), 0.0f);
  }
}

// An east-west wall H high whose top edge lies d north of a street cell hides the sun towards
// azimuth φ (north of the east-west line) below atan(H cos φ / d). At the equator the June sun
// stands north of the cell all day; at 60° N only at dawn and dusk, low and weak: the wall costs
// the equatorial cell a share of its beam that the northern one keeps.
double beam_on_street(const ExposureSky& sky, double wall, double distance) {
  double sum = 0.0;
  for (const SunStep& s : sky.sun) {
    const double north = std::cos(s.azimuth);
    const bool blocked = north > 0 && std::tan(s.elevation) < wall * north / distance;
    if (!blocked) sum += s.beam * s.direction[2];
  }
  return sum / 1000;
}

TEST(Exposure, StreetCellSouthOfAWallLosesTheBeamAnIndependentSumSays) {
  // Cells from 11 m north of the centre cell stand 20 m high: the mesh over cell centres has the
  // wall's top edge at 11 m.
  const double wall = 20.0, distance = 11.0;
  const Terrain street = test::terrain_of([&](double, double north) { return north > 10.5 ? wall : 0.0; }, 121, 1.0);
  const int col = 60, row = 60;
  double share[2];
  int i = 0;
  for (const double lat : {0.0, 60.0}) {
    SCOPED_TRACE(testing::Message() << "latitude " << lat);
    const ExposureSky sky = test::make_sky(test::clear_sky(lat, "2024-06-20T00:00Z", "2024-06-22T00:00Z", "10m"), 256);
    const double open = sky.map.irradiation(ExposureBand::direct, {0, 0, 1}) / 1000;
    const double expected = beam_on_street(sky, wall, distance);
    const ExposureBands exact = test::run_exposure(street, sky, ExposureMethod::exact, 128);
    EXPECT_NEAR(exact.direct(col, row), expected, 0.02 * open);
    const ExposureBands fast = test::run_exposure(street, sky, ExposureMethod::fast, 32);
    EXPECT_NEAR(fast.direct(col, row), expected, 0.05 * open);
    share[i++] = exact.direct(col, row) / open;
  }
  EXPECT_LT(share[0], 0.75);  // measured 0.647 (June 20-22, 10-minute steps)
  EXPECT_GT(share[1], 0.85);  // 0.917
  EXPECT_LT(share[0], share[1]);
}

TEST(Exposure, RefusesWhatItCannotServe) {
  const ExposureSky sky = test::make_sky(test::clear_sky(45, "2024-03-18T00:00Z", "2024-03-19T00:00Z", "1h"), 64);
  const Terrain flat = test::terrain_of([](double, double) { return 0.0; }, 9, 1.0);
  EXPECT_THROW(test::run_exposure(flat, sky, ExposureMethod::exact, 16, "sampled"), Error);
  EXPECT_THROW(test::run_exposure(flat, sky, ExposureMethod::fast, 128), Error);  // finer than the map
  HorizonParams p;
  p.directions = 8;
  p.spacing = AzimuthSpacing::grid_lines;
  const auto engine = make_horizon_engine("sweep", p);
  ProgressCounter progress;
  EXPECT_THROW(compute_exposure(*engine, flat, Window::whole(flat), sky, ExposureRequest{}, progress), Error);
}

}  // namespace
}  // namespace skyview
