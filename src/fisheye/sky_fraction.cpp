// svf and sky visibility of a classified fish-eye image, by per-pixel weights from the projection's
// Jacobian and by Steyn's annulus method.
#include "skyview/fisheye/sky_fraction.h"

#include <cmath>

#include "skyview/core/error.h"

namespace skyview {
namespace {

// dθ/dr for r as a fraction of the 90° radius (projection.h's formulas differentiated).
double zenith_rate(Projection p, double r) {
  switch (p) {
    case Projection::equidistant:
      return M_PI / 2;
    case Projection::equisolid:
      return std::sqrt(2.0) / std::sqrt(std::max(1e-12, 1.0 - r * r / 2.0));
    case Projection::orthographic:
      return 1.0 / std::sqrt(std::max(1e-12, 1.0 - r * r));
    case Projection::stereographic:
      return 2.0 / (1.0 + r * r);
  }
  return M_PI / 2;
}

}  // namespace

SkyFractions sky_fractions(const std::vector<std::uint8_t>& sky, int width, int height, const FisheyeFrame& frame,
                           int rings) {
  if (rings < 1 || rings > 1000) throw Error("--rings must be within 1 .. 1000");
  SkyFractions f;
  f.rings = rings;
  double all_svf = 0, sky_svf = 0, all_vis = 0, sky_vis = 0;
  std::vector<long long> ring_all(rings, 0), ring_sky(rings, 0);
  const double R = frame.radius;
  const int x0 = std::max(0, static_cast<int>(std::floor(frame.cx - R - 1))),
            x1 = std::min(width - 1, static_cast<int>(std::ceil(frame.cx + R + 1)));
  const int y0 = std::max(0, static_cast<int>(std::floor(frame.cy - R - 1))),
            y1 = std::min(height - 1, static_cast<int>(std::ceil(frame.cy + R + 1)));
  // The weights depend on the distance from the centre only: tabulated every 1/64 pixel.
  constexpr double kStep = 1.0 / 64;
  const std::size_t entries = static_cast<std::size_t>(R / kStep) + 2;
  std::vector<double> table_svf(entries), table_vis(entries);
  for (std::size_t i = 0; i < entries; ++i) {
    const double rp = i * kStep, r = rp / R;
    if (r > 1.0) continue;  // beyond 90°: no weight
    const double theta = projection_zenith(frame.projection, r);
    const double rate = zenith_rate(frame.projection, r) / R;  // dθ per pixel
    // sin θ / r stays finite at the centre: its limit is dθ/dr there.
    const double sin_over_r = rp > 1e-9 ? std::sin(theta) / rp : rate;
    table_svf[i] = std::cos(theta) * sin_over_r * rate / M_PI / 16;
    table_vis[i] = sin_over_r * rate / (2 * M_PI) / 16;
  }
  const double ring_scale = rings / (M_PI / 2);
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      double w_svf = 0, w_vis = 0;
      for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) {
          const double dx = x + (i - 1.5) / 4 - frame.cx, dy = y + (j - 1.5) / 4 - frame.cy;
          const double rp = std::sqrt(dx * dx + dy * dy);
          const std::size_t k = static_cast<std::size_t>(std::lround(rp / kStep));
          if (k >= entries) continue;
          w_svf += table_svf[k];
          w_vis += table_vis[k];
        }
      }
      if (w_svf == 0 && w_vis == 0) continue;
      const bool is_sky = sky[static_cast<std::size_t>(y) * width + x] != 0;
      all_svf += w_svf, all_vis += w_vis;
      if (is_sky) sky_svf += w_svf, sky_vis += w_vis;
      // The annulus method counts whole pixels, by the zenith angle at their centre.
      const double r = std::hypot(x - frame.cx, y - frame.cy) / R;
      if (r <= 1.0) {
        const double zenith = projection_zenith(frame.projection, r);
        const int ring = std::min(rings - 1, static_cast<int>(zenith * ring_scale));
        ++ring_all[ring];
        ring_sky[ring] += is_sky;
        ++f.pixels;
        f.sky_pixels += is_sky;
      }
    }
  }
  if (!(all_svf > 0)) throw Error("the image circle holds no pixel");
  f.svf = sky_svf / all_svf;
  f.sky_visibility = sky_vis / all_vis;
  double s = 0;
  for (int i = 0; i < rings; ++i) {
    if (ring_all[i] > 0)
      s += std::sin(M_PI * (2 * i + 1) / (2 * rings)) * static_cast<double>(ring_sky[i]) / ring_all[i];
  }
  f.svf_annulus = M_PI / (2 * rings) * s;
  return f;
}

}  // namespace skyview
