// The sky colour pipeline (Yxy -> XYZ -> linear sRGB -> tone map -> sRGB) against Preetham et al.'s
// published zenith chromaticity and the sRGB standard.
#include <gtest/gtest.h>

#include <cmath>

#include "sky_test_support.h"
#include "skyview/core/error.h"
#include "skyview/sky/sky_colour.h"

namespace skyview {
namespace {

using sky_test::kDeg;

// Preetham, Shirley & Smits 1999, App. A.2: x_z = [T² T 1] M_x [Z³ Z² Z 1]ᵀ with the printed
// matrices, evaluated by hand for T = 3 and the sun 30° high (Z = 60°): x_z = 0.24493, y_z = 0.25257
// (bluer than D65's 0.3127, 0.3290, as a clear zenith is).
TEST(SkyColour, ZenithKeepsPreethamsPublishedChromaticityThroughSrgb) {
  const SkyColour sky(3.0, 60 * kDeg, 180 * kDeg);
  const preetham::Yxy z = sky.yxy(0.0, 0.0);
  EXPECT_NEAR(z.x, 0.24493, 5e-5);
  EXPECT_NEAR(z.y, 0.25257, 5e-5);
  // Through XYZ and the Rec. 709 matrix and back: the same chromaticity.
  const preetham::Yxy back = linear_srgb_to_yxy(sky.linear(0.0, 0.0));
  EXPECT_NEAR(back.x, 0.24493, 1e-5);
  EXPECT_NEAR(back.y, 0.25257, 1e-5);
  EXPECT_NEAR(back.Y, z.Y, 1e-4 * z.Y);
  // On screen: blue above green above red, not clipped to white.
  const Srgb8 c = sky.display(0.0, 0.0);
  EXPECT_GT(c.b, c.g);
  EXPECT_GT(c.g, c.r);
  EXPECT_LT(c.b, 255);
  // T = 2, sun 60° high (Z = 30°): x_z = 0.25142, y_z = 0.25592.
  const preetham::Yxy z2 = SkyColour(2.0, 30 * kDeg, 0.0).yxy(0.0, 1.0);
  EXPECT_NEAR(z2.x, 0.25142, 5e-5);
  EXPECT_NEAR(z2.y, 0.25592, 5e-5);
}

TEST(SkyColour, ToneMapPutsTheZenithAtTheKeyAndBrightensTowardsTheSun) {
  // A key low enough that no channel of the zenith's blue clips.
  const SkyColour sky(2.5, 50 * kDeg, 90 * kDeg, 0.3);
  // The zenith's luminance maps to L / (1 + L) = 0.3: its linear luminance after scaling is 0.3.
  const preetham::LinearRgb z = sky.linear(0.0, 0.0);
  const double y = 0.2126729 * z.r + 0.7151522 * z.g + 0.0721750 * z.b;
  const Srgb8 c = sky.display(0.0, 0.0);
  auto decode = [](int v) {
    const double s = v / 255.0;
    return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
  };
  const double shown = 0.2126729 * decode(c.r) + 0.7151522 * decode(c.g) + 0.0721750 * decode(c.b);
  EXPECT_NEAR(shown, 0.3, 0.005) << y;
  // Near the sun the sky is brighter than opposite it at the same zenith angle.
  const Srgb8 near = sky.display(50 * kDeg, 100 * kDeg), far = sky.display(50 * kDeg, 270 * kDeg);
  EXPECT_GT(near.r + near.g + near.b, far.r + far.g + far.b);
}

// The fixed tone of render --time: the zenith of T = 3 with the sun 45° high (Preetham's Y_z =
// 7.33 kcd/m²) shows at key 0.5 whatever the sky; a sky of a lower sun is shown darker.
TEST(SkyColour, FixedToneShowsTwoInstantsOnOneScale) {
  const FixedTone tone = reference_tone();
  EXPECT_NEAR(tone.luminance, 7330, 10);
  EXPECT_EQ(tone.key, 0.5);
  const SkyColour reference(3.0, 45 * kDeg, 0.0, tone), keyed(3.0, 45 * kDeg, 0.0, 0.5);
  const Srgb8 a = reference.display(0.0, 0.0), b = keyed.display(0.0, 0.0);
  EXPECT_EQ(a.r, b.r);
  EXPECT_EQ(a.g, b.g);
  EXPECT_EQ(a.b, b.b);
  const Srgb8 low = SkyColour(3.0, 75 * kDeg, 0.0, tone).display(0.0, 0.0);
  const Srgb8 low_keyed = SkyColour(3.0, 75 * kDeg, 0.0, 0.5).display(0.0, 0.0);
  EXPECT_LT(low.r + low.g + low.b + 60, a.r + a.g + a.b);
  EXPECT_LT(low.r + low.g + low.b + 60, low_keyed.r + low_keyed.g + low_keyed.b);
  EXPECT_THROW(SkyColour(3.0, 45 * kDeg, 0.0, FixedTone{0.0, 0.5}), Error);
}

TEST(SkyColour, SrgbTransferFollowsTheStandard) {
  EXPECT_DOUBLE_EQ(srgb_encode(0.0), 0.0);
  EXPECT_DOUBLE_EQ(srgb_encode(1.0), 1.0);
  EXPECT_NEAR(srgb_encode(0.0031308), 12.92 * 0.0031308, 1e-12);
  EXPECT_NEAR(srgb_encode(0.18), 0.4613561, 1e-6);  // mid grey: 118 of 255
  // A colour brighter than white keeps its hue: scaled down whole, not clipped per channel.
  const Srgb8 c = to_srgb8({2.0, 1.0, 0.5}, 1.0);
  EXPECT_EQ(c.r, 255);
  EXPECT_EQ(c.g, std::lround(255 * srgb_encode(0.5)));
  EXPECT_EQ(c.b, std::lround(255 * srgb_encode(0.25)));
}

TEST(SkyColour, RefusesWhatThePreethamSkyDoesNotModel) {
  EXPECT_THROW(SkyColour(1.5, 30 * kDeg, 0.0), Error);
  EXPECT_THROW(SkyColour(3.0, 95 * kDeg, 0.0), Error);
}

}  // namespace
}  // namespace skyview
