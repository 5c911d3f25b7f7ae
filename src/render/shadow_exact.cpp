// Exact sun shadows: one Embree occlusion ray per receiver towards the sun's centre, or with
// `soft` the share of soft_samples directions over the sun's disc that reach the sky. The disc's
// samples are the centres of a k × k stratification of the square taken onto the disc by Shirley
// and Chiu's concentric map (area-preserving), so every receiver sees the same directions.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "render/shadow_methods.h"

namespace skyview::detail {

namespace {

// Directions over the disc of angular radius `radius` around `d` (frame vectors u, v across it).
std::vector<Vec3> disc_directions(const Vec3& d, const Vec3& u, const Vec3& v, double radius, int samples) {
  const int k = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(samples)))));
  const double spread = std::tan(radius);
  std::vector<Vec3> out;
  for (int j = 0; j < k; ++j) {
    for (int i = 0; i < k; ++i) {
      const double a = 2.0 * (i + 0.5) / k - 1.0, b = 2.0 * (j + 0.5) / k - 1.0;
      double r, phi;
      if (std::abs(a) > std::abs(b)) {
        r = a, phi = std::numbers::pi / 4 * (b / a);
      } else {
        r = b, phi = std::numbers::pi / 2 - std::numbers::pi / 4 * (a / b);
      }
      const double x = r * std::cos(phi) * spread, y = r * std::sin(phi) * spread;
      Vec3 w;
      for (int c = 0; c < 3; ++c) w[c] = d[c] + x * u[c] + y * v[c];
      const double n = std::sqrt(dot(w, w));
      out.push_back({w[0] / n, w[1] / n, w[2] / n});
    }
  }
  return out;
}

}  // namespace

std::vector<float> exact_visibility(const RayScene& rays, const Vec3& sun, const ShadowReceivers& receivers,
                                    const ShadowOptions& options) {
  const LightFrame frame(sun, rays.bounds());
  const std::vector<Vec3> directions =
      options.soft ? disc_directions(frame.d, frame.u, frame.v, options.sun_angular_radius, options.soft_samples)
                   : std::vector<Vec3>{frame.d};
  std::vector<float> out(receivers.points.size(), 0.0f);
  const bool normals = !receivers.normals.empty();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, out.size(), 256), [&](const auto& range) {
    for (std::size_t k = range.begin(); k != range.end(); ++k) {
      const Vec3f& p = receivers.points[k];
      const Vec3f n = normals ? receivers.normals[k] : Vec3f{0, 0, 1};
      Vec3f o;
      for (int c = 0; c < 3; ++c) o[c] = p[c] + static_cast<float>(options.ray_offset) * n[c];
      int seen = 0;
      for (const Vec3& w : directions) {
        // A direction below the receiver's own surface is blocked by it.
        if (normals && n[0] * w[0] + n[1] * w[1] + n[2] * w[2] <= 0) continue;
        const Vec3f wf{static_cast<float>(w[0]), static_cast<float>(w[1]), static_cast<float>(w[2])};
        if (!rays.occluded(o, wf)) ++seen;
      }
      out[k] = static_cast<float>(seen) / static_cast<float>(directions.size());
    }
  });
  return out;
}

}  // namespace skyview::detail
