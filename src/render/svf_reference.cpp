#include "skyview/render/svf_reference.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "skyview/core/error.h"

namespace skyview {
namespace {

std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

}  // namespace

SvfReference svf_reference(const RayScene& scene, const ViewBuffers& v, int rays, std::uint64_t seed) {
  if (rays < 1) throw UsageError("--reference-rays must be at least 1");
  const float nan = std::numeric_limits<float>::quiet_NaN();
  SvfReference out{Grid<float>(v.width, v.height, nan), Grid<float>(v.width, v.height, nan)};
  tbb::parallel_for(0, v.height, [&](int row) {
    for (int col = 0; col < v.width; ++col) {
      const std::size_t i = v.depth.index(col, row);
      if (!v.hit(i)) continue;
      const Vec3f& n = v.normal[i];
      const Vec3f& p = v.position[i];
      // An orthonormal frame about the normal (Duff et al. 2017).
      const float sign = std::copysign(1.0f, n[2]);
      const float a = -1.0f / (sign + n[2]), b = n[0] * n[1] * a;
      const Vec3f t1{1.0f + sign * n[0] * n[0] * a, sign * b, -sign * n[0]};
      const Vec3f t2{b, sign + n[1] * n[1] * a, -n[1]};
      const float offset = 1e-3f * (1.0f + std::abs(p[0]) * 1e-4f + std::abs(p[1]) * 1e-4f + std::abs(p[2]) * 1e-4f);
      const Vec3f origin{p[0] + n[0] * offset, p[1] + n[1] * offset, p[2] + n[2] * offset};
      std::uint64_t state = mix(seed ^ (std::uint64_t(row) << 32 | std::uint32_t(col)));
      int open = 0;
      for (int k = 0; k < rays; ++k) {
        state = mix(state);
        const double u1 = double(state >> 11) * 0x1.0p-53;
        state = mix(state);
        const double u2 = double(state >> 11) * 0x1.0p-53;
        // Cosine-weighted (Malley): a uniform point on the disc lifted to the hemisphere.
        const double r = std::sqrt(u1), phi = 2 * std::numbers::pi * u2;
        const double x = r * std::cos(phi), y = r * std::sin(phi), z = std::sqrt(std::max(0.0, 1 - u1));
        Vec3f d;
        for (int c = 0; c < 3; ++c) d[c] = float(x * t1[c] + y * t2[c] + z * n[c]);
        if (d[2] <= 0) continue;  // below the horizon: no sky there
        open += !scene.occluded(origin, d);
      }
      const double f = double(open) / rays;
      out.svf.values()[i] = float(f);
      out.stderr_.values()[i] = float(std::sqrt(f * (1 - f) / rays));
    }
  });
  return out;
}

}  // namespace skyview
