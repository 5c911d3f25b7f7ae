// Shadow errors against exact rays; edges probed with eight more exact rays per receiver.
#include "skyview/render/shadow_error.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <string>

#include "render/shadow_light_space.h"
#include "skyview/core/error.h"

namespace skyview {

namespace {

bool lit(float v) { return v >= 0.5f; }

}  // namespace

ShadowError shadow_error(const RayScene& rays, Vec3f sun_direction, const ShadowReceivers& receivers,
                         const ShadowResult& exact, const ShadowResult& method, const ShadowOptions& options,
                         double edge_texels) {
  const std::size_t n = receivers.points.size();
  if (exact.visibility.size() != n || method.visibility.size() != n || method.texel.size() != n) {
    throw Error("shadow_error: results of " + std::to_string(exact.visibility.size()) + " and " +
                std::to_string(method.visibility.size()) + " receivers for " + std::to_string(n) + " points");
  }
  const detail::LightFrame frame({sun_direction[0], sun_direction[1], sun_direction[2]}, rays.bounds());
  const Vec3f dir{static_cast<float>(frame.d[0]), static_cast<float>(frame.d[1]), static_cast<float>(frame.d[2])};
  const bool normals = !receivers.normals.empty();
  std::vector<char> edge(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 256), [&](const auto& range) {
    for (std::size_t k = range.begin(); k != range.end(); ++k) {
      const double r = edge_texels * method.texel[k];
      if (!(r > 0.0)) continue;
      const Vec3f& p = receivers.points[k];
      const Vec3f nf = normals ? receivers.normals[k] : Vec3f{0, 0, 1};
      const detail::Vec3 nrm{nf[0], nf[1], nf[2]};
      const double nd = detail::dot(nrm, frame.d);
      if (!(nd > 1e-3)) continue;  // facing away or grazing: its state is its own surface's
      const bool state = lit(exact.visibility[k]);
      for (int q = 0; q < 8 && !edge[k]; ++q) {
        static constexpr int kA[8] = {1, -1, 0, 0, 1, 1, -1, -1}, kB[8] = {0, 0, 1, -1, 1, -1, 1, -1};
        const double a = r * kA[q], b = r * kB[q];
        // Across the sun's rays by (a, b), then along them back onto the receiver's plane.
        const double s = -(a * detail::dot(nrm, frame.u) + b * detail::dot(nrm, frame.v)) / nd;
        Vec3f o;
        for (int c = 0; c < 3; ++c) {
          o[c] =
              static_cast<float>(p[c] + a * frame.u[c] + b * frame.v[c] + s * frame.d[c] + options.ray_offset * nf[c]);
        }
        if (rays.occluded(o, dir) == state) edge[k] = 1;  // occluded while lit here, or clear while shadowed
      }
    }
  });
  ShadowError e;
  e.receivers = n;
  double abs_sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    e.edge_receivers += edge[k];
    abs_sum += std::abs(static_cast<double>(method.visibility[k]) - exact.visibility[k]);
    const bool truth = lit(exact.visibility[k]), got = lit(method.visibility[k]);
    if (truth == got) continue;
    ++e.wrong;
    ++(edge[k] ? e.wrong_edge : e.wrong_interior);
    ++(got ? e.leaks : e.acne);
  }
  e.mean_abs = n ? abs_sum / static_cast<double>(n) : 0.0;
  return e;
}

}  // namespace skyview
