#pragma once
// A camera view in colour at one instant (skyview render --time --colour-out): pixels whose ray
// misses the scene get the clear sky's colour in their direction (sky_colour.h: Preetham Yxy ->
// XYZ -> linear sRGB -> Reinhard tone map), the sun's disc is drawn where it is in view, and the
// city is grey Lambertian surfaces lit by the irradiance at the instant (direct through its
// shadows plus the diffuse sky through the visible sky): luminance albedo · K · E / π, with K the
// luminous efficacy the Preetham sky model converts with, so surfaces and sky share one scale. One
// fixed tone mapping (reference_tone()) for every instant: two times of day compare.
#include <cstdint>
#include <span>
#include <vector>

#include "skyview/render/view_buffers.h"
#include "skyview/sky/sky_colour.h"

namespace skyview {

struct ColourViewOptions {
  double turbidity = 3.0;
  double albedo = 0.2;               // of every surface (grey: no materials in the scenes)
  double luminous_efficacy = 125.0;  // lm/W, make_preetham_sky's default
  FixedTone tone = reference_tone();
  // The sun's disc is drawn at least this many pixels in radius (its 0.27° is below a pixel of
  // wide views).
  double min_sun_radius_pixels = 1.5;
};

// The sun for the picture, in the scene's grid frame (azimuth clockwise from the scene's +y).
struct ColourViewSun {
  double zenith = 0, azimuth = 0;  // radians
  double direct_normal = 0;        // W/m², for the disc's luminance
};

// RGB, 3 bytes a pixel, rows top to bottom. `irradiance`: per pixel, W/m² on the surface (NaN or
// ignored where the pixel sees sky). Throws skyview::Error as SkyColour does (sun below the
// horizon, turbidity outside 2..10) and for an irradiance of the wrong size.
std::vector<std::uint8_t> colour_view(const Camera& camera, const ViewBuffers& view, std::span<const float> irradiance,
                                      const ColourViewSun& sun, const ColourViewOptions& options = {});

}  // namespace skyview
