#pragma once
// The colour of a clear sky for pictures (fish-eye renders, camera views): Preetham's luminance and
// chromaticity (Yxy, preetham.h) -> CIE XYZ -> linear sRGB -> tone-mapped, sRGB-encoded 8-bit.
// Tone mapping is Reinhard's L/(1 + L) on luminance, scaled so that the zenith sits at `key`, with
// the linear colour scaled by the same factor (so the chromaticity is kept until a channel clips,
// and then the colour is scaled down whole, hue kept). A FixedTone instead maps one absolute
// luminance to the key whatever the sun's height, so that pictures of two instants compare (the sky
// of a low sun is darker). Angles in radians, azimuths clockwise from north.
#include <cstdint>

#include "skyview/sky/preetham.h"

namespace skyview {

struct Srgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
};

// The sRGB transfer function (IEC 61966-2-1) of a linear value in [0, 1] (clamped).
double srgb_encode(double linear);
// Linear sRGB (any scale) to 8-bit sRGB after multiplying by `scale`: channels above 1 scale the
// colour down whole, negative channels (outside the sRGB gamut) are clipped to 0.
Srgb8 to_srgb8(const preetham::LinearRgb& c, double scale);
// The chromaticity (x, y) of a linear sRGB colour (inverse of preetham::to_linear_srgb).
preetham::Yxy linear_srgb_to_yxy(const preetham::LinearRgb& c);

// Tone mapping fixed in absolute terms: `luminance` (cd/m²) is shown at `key` (0..1).
struct FixedTone {
  double luminance = 0;
  double key = 0.5;
};

// The fixed tone of camera views at an instant (skyview render --time): the zenith of a clear sky of
// turbidity 3 with the sun 45° high (7.33 kcd/m²) shown at key 0.5.
FixedTone reference_tone();

class SkyColour {
 public:
  // `key`: the tone-mapped luminance the zenith gets (0..1), 0.5 by default. Throws skyview::Error
  // for a turbidity outside Preetham's accepted range (2..10) or a sun below the horizon (the model
  // has no twilight).
  SkyColour(double turbidity, double sun_zenith, double sun_azimuth, double key = 0.5);
  // The same sky under a fixed tone mapping (throws as above, and for a luminance that is not
  // positive or a key outside 0..1).
  SkyColour(double turbidity, double sun_zenith, double sun_azimuth, FixedTone tone);

  // Sky luminance and chromaticity looking at (zenith angle, azimuth).
  preetham::Yxy yxy(double zenith, double azimuth) const;
  // Linear sRGB (cd/m² scale) in that direction.
  preetham::LinearRgb linear(double zenith, double azimuth) const;
  // Tone-mapped display colour in that direction.
  Srgb8 display(double zenith, double azimuth) const;
  // Tone mapping of any linear colour (the sun's disc, say) with the sky's exposure.
  Srgb8 display(const preetham::LinearRgb& c) const;

 private:
  double turbidity_, sun_zenith_, sun_azimuth_;
  double exposure_;  // 1 / (luminance that maps to L = 1 before Reinhard)
};

}  // namespace skyview
