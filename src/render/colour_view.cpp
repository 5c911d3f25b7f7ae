// Sky, sun disc and lit surfaces of a camera view through one fixed tone mapping.
#include "skyview/render/colour_view.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "skyview/core/error.h"
#include "skyview/sky/sky_model.h"

namespace skyview {

std::vector<std::uint8_t> colour_view(const Camera& camera, const ViewBuffers& view, std::span<const float> irradiance,
                                      const ColourViewSun& sun, const ColourViewOptions& o) {
  const std::size_t n = static_cast<std::size_t>(view.width) * view.height;
  if (irradiance.size() != n) throw Error("colour_view: one irradiance per pixel expected");
  const SkyColour sky(o.turbidity, sun.zenith, sun.azimuth, o.tone);
  const double pi = std::numbers::pi;
  const double sx = std::sin(sun.zenith) * std::sin(sun.azimuth), sy = std::sin(sun.zenith) * std::cos(sun.azimuth),
               sz = std::cos(sun.zenith);
  // The disc: its true radius, or a few pixels where a pixel is wider than the sun.
  const double pixel_angle = camera.orthographic() ? 0.0 : camera.spec().fov_deg * pi / 180.0 / camera.height();
  const double disc = std::max(kSunAngularRadius, o.min_sun_radius_pixels * pixel_angle);
  const double cos_disc = std::cos(disc);
  // The sun's luminance, white: its normal illuminance spread over its true disc.
  const double disc_sr = 2 * pi * (1 - std::cos(kSunAngularRadius));
  const double sun_luminance = o.luminous_efficacy * sun.direct_normal / disc_sr;
  const double surface = o.albedo * o.luminous_efficacy / pi;  // cd/m² per W/m²
  std::vector<std::uint8_t> rgb(3 * n, 0);
  tbb::parallel_for(0, view.height, [&](int row) {
    for (int col = 0; col < view.width; ++col) {
      const std::size_t i = static_cast<std::size_t>(row) * view.width + col;
      Srgb8 c;
      if (view.hit(i)) {
        const double l = std::isfinite(irradiance[i]) ? std::max(0.0, surface * irradiance[i]) : 0.0;
        c = sky.display(preetham::LinearRgb{l, l, l});
      } else {
        const CameraRay ray = camera.ray(col + 0.5, row + 0.5);
        const double dx = ray.direction[0], dy = ray.direction[1], dz = ray.direction[2];
        if (dx * sx + dy * sy + dz * sz >= cos_disc && dz > 0) {
          c = sky.display(preetham::LinearRgb{sun_luminance, sun_luminance, sun_luminance});
        } else {
          // Below the horizon (past the scene's edge) the haze of the horizon continues.
          const double zenith = std::min(std::acos(std::clamp(dz, -1.0, 1.0)), pi / 2 - 1e-3);
          c = sky.display(zenith, std::atan2(dx, dy));
        }
      }
      rgb[3 * i] = c.r, rgb[3 * i + 1] = c.g, rgb[3 * i + 2] = c.b;
    }
  });
  return rgb;
}

}  // namespace skyview
