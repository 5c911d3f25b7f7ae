// Preetham 1999 zenith values against the paper's formulas written out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sky_test_support.h"
#include "skyview/error.h"
#include "skyview/preetham.h"
#include "skyview/sky_models.h"

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

}  // namespace
}  // namespace skyview
