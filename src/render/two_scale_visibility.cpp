#include "skyview/render/two_scale_visibility.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "skyview/core/error.h"

namespace skyview {
namespace {

constexpr double kPi = std::numbers::pi;

std::uint64_t splitmix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}
double unit_random(std::uint64_t& state) {
  state = splitmix(state);
  return double(state >> 11) * 0x1.0p-53;
}

struct Region {
  double horizon = 0, opening = kPi / 2;  // h(θ), h'(θ)
  bool marched = false;                   // false: the direction lies wholly behind the surface
};

// Section 5.1 in one direction: horizon and opening angles from the zenith map's solid parts.
// Where a sample raises the horizon or ends the cover, the step from the previous sample is halved
// kBisections times to find the wall's face or the cover's edge (geometrically spaced samples
// would otherwise see a face up to a step too far, and the sky too large).
constexpr int kBisections = 3;

class ZenithMarch {
 public:
  ZenithMarch(const ZenithDepthMap& z, double qx, double qy, double pz, double ux, double uy)
      : z_(z), qx_(qx), qy_(qy), pz_(pz), ux_(ux), uy_(uy) {}

  // The texel at distance d: its heights, or false outside the map.
  bool texel(double d, int& count, const float*& heights) const {
    const int col = z_.col_of(qx_ + d * ux_), row = z_.row_of(qy_ + d * uy_);
    if (!z_.in_map(col, row)) return false;
    count = z_.count(col, row);
    heights = z_.heights(col, row);
    return true;
  }
  double bottom(const float* hs, int c, int i) const {
    return i + 1 < c ? hs[i + 1] : -std::numeric_limits<double>::infinity();
  }
  bool above(double bottom) const { return bottom > pz_ + kEps; }
  // Angles are kept as their tangents (rise over distance, d > 0), which order the same.
  // The tangent of the highest part at distance d that reaches down to the point's height (all parts
  // when `all`), or -inf.
  double horizon_at(double d, bool all) const {
    int c;
    const float* hs;
    if (!texel(d, c, hs)) return -std::numeric_limits<double>::infinity();
    return horizon_of(c, hs, d, all);
  }
  double horizon_of(int c, const float* hs, double d, bool all) const {
    double h = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < c; i += 2) {
      if (all || !above(bottom(hs, c, i))) h = std::max(h, (hs[i] - pz_) / d);
    }
    return h;
  }
  // The lowest tangent of the bottoms of parts wholly above the point at distance d, or +inf if none.
  double cover_at(double d) const {
    int c;
    const float* hs;
    if (!texel(d, c, hs)) return std::numeric_limits<double>::infinity();
    return cover_of(c, hs, d);
  }
  double cover_of(int c, const float* hs, double d) const {
    double h = std::numeric_limits<double>::infinity();
    for (int i = 0; i < c; i += 2) {
      const double b = bottom(hs, c, i);
      if (above(b)) h = std::min(h, (b - pz_) / d);
    }
    return h;
  }

  static constexpr double kEps = 0.05;

 private:
  const ZenithDepthMap& z_;
  double qx_, qy_, pz_, ux_, uy_;
};

Region march_zenith(const ZenithDepthMap& z, double qx, double qy, double pz, double ux, double uy,
                    const double* distances, int samples, double opening_max) {
  const ZenithMarch m(z, qx, qy, pz, ux, uy);
  const double inf = std::numeric_limits<double>::infinity();
  double horizon_t = 0.0, opening_t = inf;  // tangents of h(θ) (at least the horizontal) and h'(θ)
  bool run = true;                          // every sample so far has a solid part wholly above the point
  double previous = 0.0;
  for (int j = 0; j < samples; ++j) {
    const double d = distances[j];
    int c;
    const float* hs;
    if (!m.texel(d, c, hs)) break;  // nothing beyond the scene
    // While under cover, parts above the point bound the opening; after it, they occlude by their tops.
    const double cover = run ? m.cover_of(c, hs, d) : inf;
    const bool overhead = std::isfinite(cover);
    const double horizon = m.horizon_of(c, hs, d, !run);
    if (overhead) opening_t = std::min(opening_t, cover);
    if (horizon > horizon_t) {
      horizon_t = horizon;
      double lo = previous, hi = d;
      for (int k = 0; k < kBisections; ++k) {
        const double mid = 0.5 * (lo + hi);
        const double a = m.horizon_at(mid, !run);
        if (a > horizon_t) {
          horizon_t = a;
          hi = mid;
        } else {
          lo = mid;
        }
      }
    }
    if (run && !overhead) {
      run = false;
      double lo = previous, hi = d;  // the cover's edge
      const bool covered = j > 0 || std::isfinite(m.cover_at(0.0));
      for (int k = 0; k < kBisections && covered; ++k) {
        const double mid = 0.5 * (lo + hi);
        const double a = m.cover_at(mid);
        if (std::isfinite(a)) {
          opening_t = std::min(opening_t, a);
          lo = mid;
        } else {
          hi = mid;
        }
      }
    }
    if (run && opening_max > 0 && d > opening_max) {
      opening_t = horizon_t;  // the opening is too far to trust: closed
      break;
    }
    previous = d;
  }
  if (run) opening_t = std::min(opening_t, horizon_t);  // under cover all the way: nothing seen
  Region r;
  r.marched = true;
  r.horizon = std::atan(horizon_t);
  r.opening = opening_t == inf ? kPi / 2 : std::atan(opening_t);
  return r;
}

Vec3d sub(const Vec3f& a, const Vec3f& b) { return {double(a[0]) - b[0], double(a[1]) - b[1], double(a[2]) - b[2]}; }
double dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Section 5.2: horizon-based ambient occlusion on the camera's buffers (Eq. 6); returns 1 − AO.
// Horizon angles are measured from the tangent plane (the paper's h(θ) − t(θ)): sin of a sample's
// elevation above it is Δ·n/|Δ|, so a flat surface occludes nothing at any viewing angle.
double fine_visibility(const ViewBuffers& v, const Camera& cam, int col, int row, const Vec3f& p, const Vec3f& n,
                       const TwoScaleOptions& o, std::uint64_t& rng) {
  const std::size_t i0 = v.depth.index(col, row);
  const double radius_px = o.fine_radius * cam.pixels_per_metre(v.depth.values()[i0]);
  if (radius_px < 1.0) return 1.0;
  const Vec3d nd{n[0], n[1], n[2]};
  const double r2 = o.fine_radius * o.fine_radius;
  const double turn = unit_random(rng) * 2 * kPi / o.directions;
  const double jitter = unit_random(rng);
  const double step = radius_px / o.samples;
  double occlusion = 0.0;
  for (int k = 0; k < o.directions; ++k) {
    const double th = turn + 2 * kPi * k / o.directions;
    const double dc = std::cos(th), dr = -std::sin(th);  // image up is row − 1
    double sin_prev = 0.0;                               // the tangent angle t(θ)
    for (int s = 0; s < o.samples; ++s) {
      const double dist = (s + jitter) * step + 0.5;
      const int c = static_cast<int>(std::floor(col + 0.5 + dc * dist));
      const int r = static_cast<int>(std::floor(row + 0.5 + dr * dist));
      if (!v.depth.in_grid(c, r)) break;
      const std::size_t i = v.depth.index(c, r);
      if (!v.hit(i)) continue;
      const Vec3d d = sub(v.position[i], p);
      const double len2 = dot(d, d);
      if (len2 >= r2 || len2 <= 0) continue;
      const double sin_h = dot(d, nd) / std::sqrt(len2);
      if (sin_h > sin_prev) {
        occlusion += (1.0 - len2 / r2) * (sin_h - sin_prev);  // W(r) of Eq. 6
        sin_prev = sin_h;
      }
    }
  }
  return std::clamp(1.0 - occlusion / o.directions, 0.0, 1.0);
}

// The fine scale along a world direction (--combine intersect): the highest elevation of what the
// camera sees within fine_radius of the point, sampled at the pixels of the points p + s·u.
double fine_horizon(const ViewBuffers& v, const Camera& cam, const Vec3f& p, double ux, double uy,
                    const TwoScaleOptions& o, double jitter) {
  double h = 0.0;
  const double r2 = o.fine_radius * o.fine_radius;
  for (int s = 0; s < o.samples; ++s) {
    const double dist = (s + jitter) * o.fine_radius / o.samples;
    double col, row, depth;
    cam.project({p[0] + dist * ux, p[1] + dist * uy, double(p[2])}, col, row, depth);
    const int c = static_cast<int>(std::floor(col)), r = static_cast<int>(std::floor(row));
    if (depth <= 0 || !v.depth.in_grid(c, r)) break;
    const std::size_t i = v.depth.index(c, r);
    if (!v.hit(i)) continue;
    const Vec3d d = sub(v.position[i], p);
    const double len2 = dot(d, d);
    const double horizontal = std::hypot(d[0], d[1]);
    if (len2 >= r2 || horizontal < 1e-6) continue;
    h = std::max(h, std::atan2(d[2], horizontal));
  }
  return h;
}

}  // namespace

double cosine_weighted_slice(double along, double up, double low, double high) {
  // a cos e + b sin e is positive for |e − e*| < π/2, e* = atan2(b, a).
  const double centre = std::atan2(up, along);
  low = std::max({low, centre - kPi / 2, 0.0});
  high = std::min({high, centre + kPi / 2, kPi / 2});
  if (high <= low) return 0.0;
  const auto primitive = [&](double e) {
    const double s = std::sin(e);
    return along * (e / 2 + std::sin(2 * e) / 4) + up * s * s / 2;
  };
  return std::max(0.0, primitive(high) - primitive(low));
}

TwoScaleBands two_scale_visibility(const ViewBuffers& v, const Camera& cam, const ZenithDepthMap& zenith,
                                   const TwoScaleOptions& o, const ExposureSampler* sampler) {
  if (o.directions < 1 || o.directions > 1024) throw UsageError("--directions must be from 1 to 1024");
  if (o.samples < 1 || o.samples > 1024) throw UsageError("--samples must be from 1 to 1024");
  if (!(o.max_distance > 0) || !std::isfinite(o.max_distance)) throw UsageError("--max-distance must be positive");
  if (!(o.fine_radius > 0) || !std::isfinite(o.fine_radius)) throw UsageError("--fine-radius must be positive");
  if (!(o.opening_max_distance >= 0) || !std::isfinite(o.opening_max_distance)) {
    throw UsageError("--opening-max-distance must be zero or positive");
  }
  if (sampler && sampler->directions() != o.directions) {
    throw Error("the exposure sampler has " + std::to_string(sampler->directions()) + " directions, not " +
                std::to_string(o.directions));
  }
  const float nan = std::numeric_limits<float>::quiet_NaN();
  TwoScaleBands b;
  b.svf = b.svf_large = b.svf_fine = Grid<float>(v.width, v.height, nan);
  if (sampler) b.exposure = b.exposure_direct = b.exposure_diffuse = Grid<float>(v.width, v.height, nan);
  const int n_dir = o.directions;
  const double slice = 2.0 / n_dir;  // (2π/N)/π
  const double first = zenith.resolution();
  const double ratio = std::pow(std::max(o.max_distance, first) / first, 1.0 / o.samples);
  tbb::parallel_for(0, v.height, [&](int row) {
    std::vector<double> distances(o.samples);
    std::vector<Region> regions(n_dir);
    for (int col = 0; col < v.width; ++col) {
      const std::size_t i = v.depth.index(col, row);
      if (!v.hit(i)) continue;
      std::uint64_t rng = splitmix(o.seed ^ (std::uint64_t(row) << 32 | std::uint32_t(col)));
      const Vec3f& p = v.position[i];
      const Vec3f& n = v.normal[i];
      const double turn = unit_random(rng) * 2 * kPi / n_dir;
      const double jitter = unit_random(rng);
      for (int j = 0; j < o.samples; ++j) distances[j] = first * std::pow(ratio, j + jitter);
      // Off the surface sideways by a texel, so that a wall's point leaves its building's texels.
      const double qx = p[0] + n[0] * zenith.resolution(), qy = p[1] + n[1] * zenith.resolution();
      const double nh = std::hypot(double(n[0]), double(n[1]));
      double large = 0.0, merged = 0.0;
      SkyExposure total;
      for (int k = 0; k < n_dir; ++k) {
        const double az = turn + 2 * kPi * k / n_dir;  // clockwise from north
        const double ux = std::sin(az), uy = std::cos(az);
        const double along = nh > 0 ? n[0] * ux + n[1] * uy : 0.0;
        Region& r = regions[k];
        r = Region{};
        if (along <= 0 && n[2] <= 0) continue;  // wholly behind the surface
        r = march_zenith(zenith, qx, qy, p[2], ux, uy, distances.data(), o.samples, o.opening_max_distance);
        large += slice * cosine_weighted_slice(along, n[2], r.horizon, r.opening);
        if (o.combine == ScaleCombination::intersect && o.fine_scale) {
          r.horizon = std::max(r.horizon, fine_horizon(v, cam, p, ux, uy, o, jitter));
          merged += slice * cosine_weighted_slice(along, n[2], r.horizon, r.opening);
        }
        if (sampler && r.opening > r.horizon && (n[2] >= 0 || nh > 0)) {
          // The sampler takes surfaces facing up or sideways; one facing down (an overhang's
          // underside) is given the exposure of a wall facing its way, an overestimate.
          const Direction nd = n[2] >= 0 ? Direction{n[0], n[1], n[2]} : Direction{n[0] / nh, n[1] / nh, 0.0};
          SkyExposure e;
          sampler->add_slice(k, float(r.horizon), float(r.opening), std::span<const Direction>(&nd, 1),
                             std::span<SkyExposure>(&e, 1), turn);
          total += e;
        }
      }
      const double fine = o.fine_scale ? fine_visibility(v, cam, col, row, p, n, o, rng) : 1.0;
      b.svf_large.values()[i] = float(std::min(1.0, large));
      b.svf_fine.values()[i] = float(fine);
      const bool multiply = o.combine == ScaleCombination::multiply;
      b.svf.values()[i] = float(multiply || !o.fine_scale ? std::min(1.0, large) * fine : std::min(1.0, merged));
      if (sampler) {
        const double w = multiply ? fine : 1.0;
        b.exposure_direct.values()[i] = float(total.direct * w / 1000);
        b.exposure_diffuse.values()[i] = float(total.diffuse * w / 1000);
        b.exposure.values()[i] = float(total.total() * w / 1000);
      }
    }
  });
  return b;
}

}  // namespace skyview
