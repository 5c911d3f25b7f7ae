// Cascaded maps: the receivers split by their distance from the eye, one depth map fitted to each
// cascade's receivers, so near receivers get small texels. CSM filters each with PCF (Dimitrov
// 2007; splits of Zhang et al. 2006); the hybrid maps (HSM, Kolivand & Sunar) hold layered variance
// maps in each, split logarithmically in distance and in depth.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "render/shadow_methods.h"

namespace skyview::detail {

std::vector<double> cascade_splits(double near, double far, int cascades, double lambda) {
  std::vector<double> c(static_cast<std::size_t>(cascades) + 1);
  for (int i = 0; i <= cascades; ++i) {
    const double f = static_cast<double>(i) / cascades;
    c[i] = lambda * near * std::pow(far / near, f) + (1.0 - lambda) * (near + (far - near) * f);
  }
  c.front() = near, c.back() = far;
  return c;
}

void cascaded_visibility(const RayScene& rays, const LightFrame& frame, const std::vector<LightReceiver>& receivers,
                         const std::vector<Vec3f>& points, ShadowMethod method, const ShadowOptions& o,
                         ShadowResult& out) {
  using Clock = std::chrono::steady_clock;
  const Vec3f& eye = *o.eye;
  std::vector<double> distance(points.size());
  double near = std::numeric_limits<double>::infinity(), far = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double dx = points[k][0] - eye[0], dy = points[k][1] - eye[1], dz = points[k][2] - eye[2];
    distance[k] = std::sqrt(dx * dx + dy * dy + dz * dz);
    near = std::min(near, distance[k]), far = std::max(far, distance[k]);
  }
  // The logarithm needs a near plane in front of the eye: the nearest receiver, at least 0.5 m.
  near = std::max(near, 0.5);
  far = std::max(far, near * 1.001);
  const bool hybrid = method == ShadowMethod::hsm;
  const std::vector<double> splits =
      cascade_splits(near, far, o.cascades, hybrid ? o.hsm_split_lambda : o.split_lambda);
  std::vector<std::vector<std::size_t>> members(static_cast<std::size_t>(o.cascades));
  for (std::size_t k = 0; k < points.size(); ++k) {
    const int c =
        static_cast<int>(std::upper_bound(splits.begin() + 1, splits.end() - 1, distance[k]) - (splits.begin() + 1));
    members[static_cast<std::size_t>(c)].push_back(k);
  }
  out.visibility.assign(points.size(), 0.0f);
  out.texel.assign(points.size(), 0.0f);
  const int layers = hybrid ? o.hsm_layers : 0;
  for (const std::vector<std::size_t>& which : members) {
    if (which.empty()) continue;
    const auto t0 = Clock::now();
    const DepthMap map = render_depth_map(rays, frame, receivers, which, o.map_size, filter_pad(o.pcf_kernel));
    const std::vector<double> bounds = hybrid ? layer_bounds(map, layers, /*logarithmic=*/true) : std::vector<double>{};
    const auto t1 = Clock::now();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, which.size(), 512), [&](const auto& range) {
      for (std::size_t q = range.begin(); q != range.end(); ++q) {
        const std::size_t k = which[q];
        const double v =
            hybrid ? layered_lookup(map, bounds, receivers[k], o, o.layer_overlap) : pcf_lookup(map, receivers[k], o);
        out.visibility[k] = static_cast<float>(v);
        out.texel[k] = static_cast<float>(map.texel);
      }
    });
    out.map_seconds += std::chrono::duration<double>(t1 - t0).count();
    out.lookup_seconds += std::chrono::duration<double>(Clock::now() - t1).count();
    out.map_bytes += map.bytes();
    ++out.maps;
  }
}

}  // namespace skyview::detail
