// svf and sky visibility of a classified fish-eye image, by per-pixel weights from the projection's
// Jacobian and by Steyn's annulus method.
#include "skyview/fisheye/sky_fraction.h"

#include <algorithm>
#include <cmath>

#include "skyview/core/error.h"

namespace skyview {

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
  // The weights depend on the distance from the centre only: tabulated every 1/64 pixel as the
  // exact mean density over each thin ring, from the weight within radius r, sin²θ(r) for svf and
  // 1 − cos θ(r) for sky visibility (each 1 over the hemisphere). The Jacobian itself would do at
  // the ring's middle but for the orthographic projection's rim, where dθ/dr diverges.
  constexpr double kStep = 1.0 / 64;
  const std::size_t entries = static_cast<std::size_t>(R / kStep) + 2;
  std::vector<double> table_svf(entries, 0.0), table_vis(entries, 0.0);
  auto within = [&](double rp, double& w_svf, double& w_vis) {
    const double theta = projection_zenith(frame.projection, std::min(rp / R, 1.0));
    w_svf = std::sin(theta) * std::sin(theta);
    w_vis = 1.0 - std::cos(theta);
  };
  for (std::size_t i = 0; i < entries; ++i) {
    const double lo = std::max(0.0, (i - 0.5) * kStep), hi = (i + 0.5) * kStep;
    if (lo >= R) break;
    double s_lo, v_lo, s_hi, v_hi;
    within(lo, s_lo, v_lo);
    within(hi, s_hi, v_hi);
    const double area = M_PI * (hi * hi - lo * lo) * 16;  // 16 samples per pixel
    table_svf[i] = (s_hi - s_lo) / area;
    table_vis[i] = (v_hi - v_lo) / area;
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
  f.coverage = std::min(1.0, all_svf);  // the weights over the whole circle add up to 1
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
