#pragma once
// Sky fractions of a classified fish-eye image: the svf (cosine-weighted, as the radiative sky-view
// factor of a horizontal surface) and sky visibility (the solid angle's share of the hemisphere),
// with per-pixel weights from the projection's Jacobian, and the annulus method of Steyn (1980) for
// comparison.
#include <cstdint>
#include <vector>

#include "skyview/fisheye/projection.h"

namespace skyview {

struct SkyFractions {
  double svf = 0;             // Σ_sky w / Σ w, w = ∫_pixel cos θ sin θ (dθ/dr) / (π r) dA
  double sky_visibility = 0;  // the same with w = ∫_pixel sin θ (dθ/dr) / (2π r) dA (solid angle / 2π)
  double svf_annulus = 0;     // (π/2n) Σ_i sin(π(2i − 1)/2n) p_i/t_i over n rings of equal zenith angle
  int rings = 0;
  // The share of the hemisphere's svf weight that the image holds: below 1 where the 90° circle
  // runs off the image (a full-frame fish-eye), whose missing part the fractions leave out.
  double coverage = 0;
  long long pixels = 0, sky_pixels = 0;  // within θ ≤ 90°
};

// `sky`: width * height, non-zero where sky; `frame`: the hemisphere's place and projection. Each
// pixel's weights are the mean at 4 x 4 points inside it of the weight density, itself exact over
// rings 1/64 pixel wide (from the weights within a radius, sin²θ and 1 − cos θ), so pixels cut by
// the 90° circle count their part inside. Throws skyview::Error for rings outside 1 .. 1000 or a circle that
// holds no pixel.
SkyFractions sky_fractions(const std::vector<std::uint8_t>& sky, int width, int height, const FisheyeFrame& frame,
                           int rings = 36);

}  // namespace skyview
