// Preetham 1999 zenith values against the paper's formulas written out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sky_test_support.h"
#include "skyview/core/error.h"
#include "skyview/sky/preetham.h"
#include "skyview/sky/sky_models.h"

namespace skyview {
namespace {

using sky_test::kDeg;

TEST(Preetham, ZenithLuminanceFollowsThePaper) {
  // Y_z = (4.0453 T − 4.9710) tan χ − 0.2155 T + 2.4192 (kcd/m²), χ = (4/9 − T/120)(π − 2Z).
  // T = 2, Z = 0: χ = (4/9 − 1/60)·π = 1.343904; tan χ = 4.3315
  const double chi = (4.0 / 9.0 - 2.0 / 120.0) * std::numbers::pi;
  EXPECT_NEAR(chi, 1.3439035, 1e-6);
  EXPECT_NEAR(preetham::zenith(2.0, 0.0).Y, 1000 * ((4.0453 * 2 - 4.9710) * std::tan(chi) - 0.2155 * 2 + 2.4192), 1e-9);
  EXPECT_NEAR(preetham::zenith(2.0, 0.0).Y / 1000, 15.5007, 1e-3);  // computed by hand from the printed formula
  // T = 5, Z = 60°: χ = (4/9 − 1/24)(π/3) = 0.42178, tan χ = 0.44872; Y = 15.2555·0.44878 − 1.0775 + 2.4192
  EXPECT_NEAR(preetham::zenith(5.0, 60 * kDeg).Y / 1000, 8.1871, 1e-3);
}

TEST(Preetham, ZenithChromaticityFollowsThePaper) {
  // x_z = [T² T 1]·M_x·[Z³ Z² Z 1]ᵀ. At Z = 0 only the last column counts:
  // x = 0·T² + 0.00394 T + 0.25886, y = 0.00516 T + 0.26688.
  EXPECT_NEAR(preetham::zenith(3.0, 0.0).x, 0.00394 * 3 + 0.25886, 1e-12);
  EXPECT_NEAR(preetham::zenith(3.0, 0.0).y, 0.00516 * 3 + 0.26688, 1e-12);
  // T = 2, Z = 1 rad: every column sums.
  const double x = 4 * (0.00166 - 0.00375 + 0.00209 + 0.0) + 2 * (-0.02903 + 0.06377 - 0.03202 + 0.00394) +
                   (0.11693 - 0.21196 + 0.06052 + 0.25886);
  const double y = 4 * (0.00275 - 0.00610 + 0.00317 + 0.0) + 2 * (-0.04214 + 0.08970 - 0.04153 + 0.00516) +
                   (0.15346 - 0.26756 + 0.06670 + 0.26688);
  EXPECT_NEAR(preetham::zenith(2.0, 1.0).x, x, 1e-12);
  EXPECT_NEAR(preetham::zenith(2.0, 1.0).y, y, 1e-12);
}

TEST(Preetham, SkyEqualsZenithValueAtTheZenith) {
  const preetham::Yxy z = preetham::zenith(2.5, 35 * kDeg);
  const preetham::Yxy s = preetham::sky(2.5, 35 * kDeg, 0.0, 35 * kDeg);
  EXPECT_NEAR(s.Y, z.Y, 1e-9 * z.Y);
  EXPECT_NEAR(s.x, z.x, 1e-12);
  EXPECT_NEAR(s.y, z.y, 1e-12);
  // Brighter towards the sun than opposite it, at the same zenith angle.
  EXPECT_GT(preetham::sky(2.5, 35 * kDeg, 35 * kDeg, 10 * kDeg).Y,
            preetham::sky(2.5, 35 * kDeg, 35 * kDeg, 70 * kDeg).Y);
}

// The distribution F(θ,γ)/F(0,Z) of Y, x and y away from the zenith, from the paper's table
// (App. A.2, the shared CSV's "paper" rows) written out here.
TEST(Preetham, DistributionFollowsThePaperTable) {
  SKYVIEW_REQUIRE_SHARED(path, "sky_coefficients/preetham1999_distribution.csv");
  const double T = 3.0, Z = 40 * kDeg, theta = 60 * kDeg, gamma = 50 * kDeg;
  double k[3][5] = {};  // Y, x, y by A..E
  int found = 0;
  for (const auto& r : sky_test::read_csv(path)) {
    if (r.at("variant") != "paper") continue;
    const int c = r.at("component") == "Y" ? 0 : r.at("component") == "x" ? 1 : 2;
    k[c][r.at("param")[0] - 'A'] = std::stod(r.at("slope_per_T")) * T + std::stod(r.at("intercept"));
    ++found;
  }
  ASSERT_EQ(found, 15);
  auto F = [](const double* p, double th, double ga) {
    return (1 + p[0] * std::exp(p[1] / std::cos(th))) *
           (1 + p[2] * std::exp(p[3] * ga) + p[4] * std::pow(std::cos(ga), 2));
  };
  const preetham::Yxy z = preetham::zenith(T, Z);
  const preetham::Yxy s = preetham::sky(T, Z, theta, gamma);
  EXPECT_NEAR(s.Y / z.Y, F(k[0], theta, gamma) / F(k[0], 0.0, Z), 1e-9);
  EXPECT_NEAR(s.x / z.x, F(k[1], theta, gamma) / F(k[1], 0.0, Z), 1e-9);
  EXPECT_NEAR(s.y / z.y, F(k[2], theta, gamma) / F(k[2], 0.0, Z), 1e-9);
}

TEST(Preetham, ColourConversionKeepsD65White) {
  const preetham::LinearRgb w = preetham::to_linear_srgb(preetham::to_xyz({1.0, 0.31271, 0.32902}));
  EXPECT_NEAR(w.r, 1.0, 2e-3);
  EXPECT_NEAR(w.g, 1.0, 2e-3);
  EXPECT_NEAR(w.b, 1.0, 2e-3);
}

TEST(Preetham, BroadbandSkyAndSunArePlausible) {
  const auto model = make_preetham_sky(2.5);
  SkyConditions c;
  c.sun_zenith = 30 * kDeg;
  const auto sky = model->at(c);
  const double dhi = sky->diffuse_horizontal();
  EXPECT_GT(dhi, 50.0);
  EXPECT_LT(dhi, 250.0);
  EXPECT_GT(sky->direct_normal(), 700.0);
  EXPECT_LT(sky->direct_normal(), 1200.0);
  EXPECT_THROW(make_preetham_sky(12.0), Error);
}

// Below T = 2, the bottom of the fit, the zenith's normalisation F(0, Z) heads for zero (its factor
// 1 + A e^B vanishes at T = 1.643), and the "clearest" sky had the most diffuse light: 374 W/m² at
// T = 1.7 against 195 at T = 2 (sun 30° from the zenith), and a global horizontal above the
// extraterrestrial one. The range now starts at 2, and from there diffuse light grows with haze.
TEST(Preetham, TurbidityStartsAtTheFitsBottomAndDiffuseGrowsWithHaze) {
  EXPECT_THROW(make_preetham_sky(1.9), Error);
  SkyConditions c;
  c.sun_zenith = 30 * kDeg;
  double previous = 0.0;
  for (const double T : {2.0, 2.5, 3.0, 4.0, 6.0}) {
    const double dhi = make_preetham_sky(T)->at(c)->diffuse_horizontal();
    EXPECT_GT(dhi, previous) << "T = " << T;
    previous = dhi;
  }
}

}  // namespace
}  // namespace skyview
