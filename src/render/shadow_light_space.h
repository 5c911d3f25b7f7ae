#pragma once
// What every shadow-map method shares: the sun's orthographic frame, receivers in it, depth maps
// rendered by Embree over a set of receivers, and the bilinear filter footprint their lookups use.
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "skyview/render/shadow_maps.h"

namespace skyview::detail {

using Vec3 = std::array<double, 3>;

inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The sun's frame: d towards the sun, u and v across it. A point's light-space position is
// (p·u, p·v) and its depth top − p·d, the distance below a plane above the whole scene.
struct LightFrame {
  Vec3 d, u, v;
  double top = 0;  // above every scene vertex along d
  double far = 0;  // below every scene vertex: the depth of texels whose ray meets nothing

  LightFrame(const Vec3& sun, const std::array<Vec3f, 2>& bounds);
};

// Receivers as the maps see them: light-space position and depth, and the depth's slope across
// the map (from the normal: dz/dx = n·u / n·d), capped for grazing surfaces.
struct LightReceiver {
  double x = 0, y = 0, z = 0;
  double dzdx = 0, dzdy = 0;
  double tan_angle = 0;  // tan of the angle between normal and sun, capped at 10
  bool faces_sun = true;
};

std::vector<LightReceiver> light_receivers(const LightFrame& frame, const ShadowReceivers& receivers);

// One square-texel depth map over a light-space rectangle: texel (i, j) has its centre at
// (x0 + (i + 0.5)·texel, y0 + (j + 0.5)·texel).
struct DepthMap {
  double x0 = 0, y0 = 0, texel = 1;
  int nx = 0, ny = 0;
  std::vector<float> depth;        // nx·ny, rows of constant j
  float min_hit = 0, max_hit = 0;  // over the texels whose ray met the scene

  float at(int i, int j) const { return depth[static_cast<std::size_t>(j) * nx + i]; }
  std::size_t bytes() const { return depth.size() * sizeof(float); }
};

// Renders the map over the light-space bounds of `which` receivers (all when empty), map_size
// texels on the longer side, with `pad` texels of margin for the filter.
DepthMap render_depth_map(const RayScene& rays, const LightFrame& frame, const std::vector<LightReceiver>& receivers,
                          const std::vector<std::size_t>& which, int map_size, int pad);

// Calls f(i, j, weight, dx, dy) for the texels under a kernel × kernel box of bilinear taps one
// texel apart centred on (x, y); dx, dy are the tap's offset from (x, y) in metres. The weights
// sum to 1.
template <class F>
void filter_footprint(const DepthMap& map, double x, double y, int kernel, F&& f) {
  const double fx = (x - map.x0) / map.texel - 0.5, fy = (y - map.y0) / map.texel - 0.5;
  const int half = kernel / 2;
  const double tap_weight = 1.0 / (kernel * kernel);
  for (int b = -half; b <= half; ++b) {
    for (int a = -half; a <= half; ++a) {
      const double tx = fx + a, ty = fy + b;
      const int i0 = static_cast<int>(std::floor(tx)), j0 = static_cast<int>(std::floor(ty));
      const double wx = tx - i0, wy = ty - j0;
      for (int dj = 0; dj <= 1; ++dj) {
        for (int di = 0; di <= 1; ++di) {
          const double w = (di ? wx : 1 - wx) * (dj ? wy : 1 - wy) * tap_weight;
          if (w <= 0) continue;
          const int i = std::min(std::max(i0 + di, 0), map.nx - 1), j = std::min(std::max(j0 + dj, 0), map.ny - 1);
          f(i, j, w, a * map.texel, b * map.texel);
        }
      }
    }
  }
}

// The margin a filter of `kernel` taps needs around the receivers.
inline int filter_pad(int kernel) { return kernel / 2 + 2; }

// Lookups (per receiver, visibility 0 .. 1):
// percentage-closer filtering with the receiver's plane depth at each tap.
double pcf_lookup(const DepthMap& map, const LightReceiver& r, const ShadowOptions& o);
// Chebyshev's bound on the moments of depths warped into [lo, hi] (lo = −inf, hi = +inf: plain VSM).
double variance_lookup(const DepthMap& map, const LightReceiver& r, const ShadowOptions& o, double lo, double hi);
// The layer bounds s_0 < ... < s_L over the map's depths: uniform, or logarithmic from the nearest
// occluder (HSM).
std::vector<double> layer_bounds(const DepthMap& map, int layers, bool logarithmic);
// Layered VSM lookup: the receiver's layer by its depth, the warp starting `overlap` of that
// layer's depth before its near bound.
double layered_lookup(const DepthMap& map, const std::vector<double>& bounds, const LightReceiver& r,
                      const ShadowOptions& o, double overlap);

// The constant plus slope-scaled bias at a map of this texel.
inline double lookup_bias(const LightReceiver& r, const ShadowOptions& o, double texel) {
  return o.depth_bias + o.slope_bias * texel * r.tan_angle;
}

}  // namespace skyview::detail
