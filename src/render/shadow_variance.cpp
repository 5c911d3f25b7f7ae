// Variance shadow maps (Donnelly & Lauritzen 2006) and their layered form (Lauritzen & McCool
// 2008; the hybrid maps' layers): the mean μ and second moment of the depths under the footprint
// bound the lit share of a receiver at depth t > μ by Chebyshev's one-tailed inequality,
// p ≤ σ² / (σ² + (t − μ)²). Layers warp depths into [lo, hi] first, so occluders in front of a
// receiver's layer all sit at 0 and cannot spread the variance that lets light bleed through.
#include <algorithm>
#include <cmath>

#include "render/shadow_light_space.h"

namespace skyview::detail {

double variance_lookup(const DepthMap& map, const LightReceiver& r, const ShadowOptions& o, double lo, double hi) {
  if (!r.faces_sun) return 0.0;
  const bool warped = std::isfinite(lo);
  const double width = std::isfinite(hi) && warped ? hi - lo : 1.0;
  auto warp = [&](double z) {
    if (!warped) return z;
    return (std::min(std::max(z, lo), hi) - lo) / width;
  };
  double m1 = 0.0, m2 = 0.0;
  filter_footprint(map, r.x, r.y, o.pcf_kernel, [&](int i, int j, double w, double, double) {
    const double z = warp(map.at(i, j));
    m1 += w * z;
    m2 += w * z * z;
  });
  const double t = warp(r.z - lookup_bias(r, o, map.texel));
  if (t <= m1) return 1.0;
  const double variance = std::max(m2 - m1 * m1, o.min_variance / (width * width));
  const double d = t - m1;
  const double p = variance / (variance + d * d);
  // Light-bleeding reduction: the bound's tail below the given share is cut to 0.
  const double a = o.light_bleed_reduction;
  return std::clamp((p - a) / (1.0 - a), 0.0, 1.0);
}

double layered_lookup(const DepthMap& map, const std::vector<double>& bounds, const LightReceiver& r,
                      const ShadowOptions& o, double overlap) {
  const int layers = static_cast<int>(bounds.size()) - 1;
  int k = static_cast<int>(std::upper_bound(bounds.begin(), bounds.end(), r.z) - bounds.begin()) - 1;
  k = std::clamp(k, 0, layers - 1);
  // The warp starts `overlap` of the layer's depth before it, so that a receiver near its layer's
  // front is not as close to the occluders clamped there as it is to its own surface.
  const double width =
      std::isfinite(bounds[k + 1]) ? bounds[k + 1] - bounds[k] : (k > 0 ? bounds[k] - bounds[k - 1] : 1.0);
  const double lo = bounds[k] - overlap * width, hi = bounds[k + 1];
  return variance_lookup(map, r, o, lo, hi);
}

}  // namespace skyview::detail
