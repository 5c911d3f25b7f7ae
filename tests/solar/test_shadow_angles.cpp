// Façade shadow angles (hybrid shadow maps paper, Eqs. 1-2).
#include <gtest/gtest.h>

#include <cmath>

#include "skyview/solar/shadow_angles.h"

using namespace skyview;

TEST(SolarShadowAngles, FacingTheSun) {
  const ShadowAngles a = shadow_angles(180.0, 40.0, 180.0);
  EXPECT_NEAR(a.horizontal_deg, 0.0, 1e-12);
  EXPECT_NEAR(a.vertical_deg, 40.0, 1e-12);
  EXPECT_TRUE(a.sun_on_facade);
}

TEST(SolarShadowAngles, ObliqueSunRaisesTheProfileAngle) {
  const ShadowAngles a = shadow_angles(225.0, 30.0, 180.0);
  EXPECT_NEAR(a.horizontal_deg, 45.0, 1e-12);
  EXPECT_NEAR(a.vertical_deg, std::atan(std::tan(30.0 * M_PI / 180) / std::cos(M_PI / 4)) * 180 / M_PI, 1e-12);
  EXPECT_NEAR(a.vertical_deg, 39.2315, 1e-4);
  EXPECT_NEAR(shadow_angles(135.0, 30.0, 180.0).horizontal_deg, -45.0, 1e-12);
}

TEST(SolarShadowAngles, WrapsAndBehind) {
  EXPECT_NEAR(shadow_angles(10.0, 20.0, 350.0).horizontal_deg, 20.0, 1e-12);
  const ShadowAngles behind = shadow_angles(10.0, 20.0, 180.0);
  EXPECT_NEAR(behind.horizontal_deg, -170.0, 1e-12);
  EXPECT_TRUE(std::isnan(behind.vertical_deg));
  EXPECT_FALSE(behind.sun_on_facade);
  EXPECT_FALSE(shadow_angles(180.0, -2.0, 180.0).sun_on_facade);  // below the horizon
  EXPECT_LT(shadow_angles(180.0, -2.0, 180.0).vertical_deg, 0.0);
}
