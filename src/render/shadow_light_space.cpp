// The sun's orthographic frame and depth maps rendered in it by Embree.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "render/shadow_light_space.h"

namespace skyview::detail {

namespace {

constexpr double kMaxTan = 10.0;

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

Vec3 unit(const Vec3& a) {
  const double n = std::sqrt(dot(a, a));
  return {a[0] / n, a[1] / n, a[2] / n};
}

}  // namespace

LightFrame::LightFrame(const Vec3& sun, const std::array<Vec3f, 2>& bounds) : d(unit(sun)) {
  // u across the sun's azimuth (horizontal), v completing a right-handed frame.
  const Vec3 up{0, 0, 1};
  const Vec3 across = cross(up, d);
  u = dot(across, across) > 1e-12 ? unit(across) : Vec3{1, 0, 0};
  v = cross(d, u);
  double hi = -std::numeric_limits<double>::infinity(), lo = -hi;
  for (int k = 0; k < 8; ++k) {
    const Vec3 corner{bounds[k & 1][0], bounds[(k >> 1) & 1][1], bounds[(k >> 2) & 1][2]};
    hi = std::max(hi, dot(corner, d));
    lo = std::min(lo, dot(corner, d));
  }
  top = hi + 1.0;
  far = top - lo + 1.0;
}

std::vector<LightReceiver> light_receivers(const LightFrame& frame, const ShadowReceivers& receivers) {
  std::vector<LightReceiver> out(receivers.points.size());
  const bool normals = !receivers.normals.empty();
  for (std::size_t k = 0; k < out.size(); ++k) {
    const Vec3f& pf = receivers.points[k];
    const Vec3 p{pf[0], pf[1], pf[2]};
    LightReceiver& r = out[k];
    r.x = dot(p, frame.u);
    r.y = dot(p, frame.v);
    r.z = frame.top - dot(p, frame.d);
    if (!normals) continue;
    const Vec3f& nf = receivers.normals[k];
    const Vec3 n{nf[0], nf[1], nf[2]};
    const double c = dot(n, frame.d);
    r.faces_sun = c > 0;
    if (!r.faces_sun) continue;
    // On the receiver's plane n·p = const: moving x along u changes depth by (n·u)/(n·d).
    const double cap = kMaxTan;
    r.dzdx = std::clamp(dot(n, frame.u) / c, -cap, cap);
    r.dzdy = std::clamp(dot(n, frame.v) / c, -cap, cap);
    r.tan_angle = std::min(std::sqrt(std::max(0.0, 1 - c * c)) / c, cap);
  }
  return out;
}

DepthMap render_depth_map(const RayScene& rays, const LightFrame& frame, const std::vector<LightReceiver>& receivers,
                          const std::vector<std::size_t>& which, int map_size, int pad) {
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = x_hi;
  auto include = [&](const LightReceiver& r) {
    x_lo = std::min(x_lo, r.x), x_hi = std::max(x_hi, r.x);
    y_lo = std::min(y_lo, r.y), y_hi = std::max(y_hi, r.y);
  };
  if (which.empty()) {
    for (const LightReceiver& r : receivers) include(r);
  } else {
    for (std::size_t k : which) include(receivers[k]);
  }
  DepthMap m;
  const int inner = std::max(1, map_size - 2 * pad);
  const double extent = std::max({x_hi - x_lo, y_hi - y_lo, 1e-3});
  m.texel = extent / inner;
  m.nx = std::min(map_size, static_cast<int>(std::ceil((x_hi - x_lo) / m.texel)) + 2 * pad);
  m.ny = std::min(map_size, static_cast<int>(std::ceil((y_hi - y_lo) / m.texel)) + 2 * pad);
  m.nx = std::max(m.nx, 1), m.ny = std::max(m.ny, 1);
  // Centre the receivers' bounds in the map.
  m.x0 = 0.5 * (x_lo + x_hi) - 0.5 * m.nx * m.texel;
  m.y0 = 0.5 * (y_lo + y_hi) - 0.5 * m.ny * m.texel;
  m.depth.assign(static_cast<std::size_t>(m.nx) * m.ny, static_cast<float>(frame.far));
  const Vec3f dir{static_cast<float>(-frame.d[0]), static_cast<float>(-frame.d[1]), static_cast<float>(-frame.d[2])};
  tbb::parallel_for(0, m.ny, [&](int j) {
    const double y = m.y0 + (j + 0.5) * m.texel;
    for (int i = 0; i < m.nx; ++i) {
      const double x = m.x0 + (i + 0.5) * m.texel;
      Vec3f o;
      for (int c = 0; c < 3; ++c) o[c] = static_cast<float>(x * frame.u[c] + y * frame.v[c] + frame.top * frame.d[c]);
      if (const auto hit = rays.intersect(o, dir)) m.depth[static_cast<std::size_t>(j) * m.nx + i] = hit->t;
    }
  });
  m.min_hit = static_cast<float>(frame.far), m.max_hit = 0;
  for (float z : m.depth) {
    if (z >= static_cast<float>(frame.far)) continue;
    m.min_hit = std::min(m.min_hit, z), m.max_hit = std::max(m.max_hit, z);
  }
  if (m.max_hit < m.min_hit) m.min_hit = m.max_hit = static_cast<float>(frame.far);
  return m;
}

std::vector<double> layer_bounds(const DepthMap& map, int layers, bool logarithmic) {
  // From just before the nearest occluder to the farthest surface the map sees; the last layer
  // reaches on to infinity for receivers below that (under a bridge).
  const double lo = std::max(0.0, static_cast<double>(map.min_hit) - 0.01);
  const double far = std::max(lo + 1.0, static_cast<double>(map.max_hit) + 0.01);
  std::vector<double> s(static_cast<std::size_t>(layers) + 1);
  const double range = far - lo;
  for (int i = 0; i <= layers; ++i) {
    const double f = static_cast<double>(i) / layers;
    // Logarithmic from the nearest occluder: thin layers near it, as the paper's curve.
    s[i] = logarithmic ? lo + (std::pow(range + 1.0, f) - 1.0) : lo + range * f;
  }
  s.back() = std::numeric_limits<double>::infinity();
  return s;
}

}  // namespace skyview::detail
