#pragma once
// The per-pixel ray casting the ray-cast references share (svf_reference.cpp,
// exposure_reference.cpp): rays leave a pixel's hit point just off its surface, in a frame about its
// normal, with a reproducible random sequence per pixel.
#include <cmath>
#include <cstdint>
#include <numbers>

#include <algorithm>

#include "skyview/scene/scene.h"

namespace skyview::detail {

inline std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

class PixelHemisphere {
 public:
  PixelHemisphere(const Vec3f& position, const Vec3f& normal, std::uint64_t seed, int col, int row) : n_(normal) {
    // An orthonormal frame about the normal (Duff et al. 2017).
    const Vec3f& n = normal;
    const float sign = std::copysign(1.0f, n[2]);
    const float a = -1.0f / (sign + n[2]), b = n[0] * n[1] * a;
    t1_ = {1.0f + sign * n[0] * n[0] * a, sign * b, -sign * n[0]};
    t2_ = {b, sign + n[1] * n[1] * a, -n[1]};
    const Vec3f& p = position;
    const float offset = 1e-3f * (1.0f + std::abs(p[0]) * 1e-4f + std::abs(p[1]) * 1e-4f + std::abs(p[2]) * 1e-4f);
    origin_ = {p[0] + n[0] * offset, p[1] + n[1] * offset, p[2] + n[2] * offset};
    state_ = mix(seed ^ (std::uint64_t(row) << 32 | std::uint32_t(col)));
  }

  const Vec3f& origin() const { return origin_; }
  const Vec3f& normal() const { return n_; }

  // The next uniform number in [0, 1).
  double uniform() {
    state_ = mix(state_);
    return double(state_ >> 11) * 0x1.0p-53;
  }

  // A cosine-weighted direction about the normal from two uniform numbers (Malley: a uniform point
  // on the disc lifted to the hemisphere); its density is (n·ω)/π.
  Vec3f cosine_direction(double u1, double u2) const {
    const double r = std::sqrt(u1), phi = 2 * std::numbers::pi * u2;
    const double x = r * std::cos(phi), y = r * std::sin(phi), z = std::sqrt(std::max(0.0, 1 - u1));
    Vec3f d;
    for (int c = 0; c < 3; ++c) d[c] = float(x * t1_[c] + y * t2_[c] + z * n_[c]);
    return d;
  }

 private:
  Vec3f n_, t1_, t2_, origin_;
  std::uint64_t state_;
};

}  // namespace skyview::detail
