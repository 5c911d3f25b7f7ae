// Exact horizons in linear time per direction. For one azimuth, parallel lines one cell apart
// cover the raster (one sample per row, or per column, along that azimuth). Walking a line from its
// far end back towards the viewer keeps the upper convex hull of the profile already seen; the
// horizon of the current cell is its tangent to that hull, which is also its neighbour once it
// is pushed onto the hull (Andrew's monotone chain), so each cell costs amortised O(1) and the
// search radius is unlimited. The idea follows the hull-based horizon algorithms of Stewart
// (1998, "Fast horizon computation at all points of a terrain with visibility and shading
// applications") and its sweep variants.
//
// Earth curvature: the apparent height of point j seen from i is z_j - c (t_j - t_i)^2. With
// transformed heights z' = z - c t^2 the slope from i to j becomes the true slope minus 2 c t_i,
// the same shift for every j, so the hull of z' still picks the true horizon exactly.
//
// Surface model: lines are sampled by linear interpolation between cell centres at every major-axis
// step, as the march does; a cell's horizon interpolates those of its two neighbouring lines.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "earth_curvature.h"
#include "methods.h"
#include "skyview/error.h"

namespace skyview::detail {
namespace {

struct HullPoint {
  double t, z;
};

// Slope of the tangent from p (nearer than every hull point) to an upper hull stored far-to-
// near: slopes from an outside point along a convex chain are unimodal, so bisection finds it.
inline double tangent_slope(const std::vector<HullPoint>& hull, const HullPoint& p) {
  auto slope = [&](std::size_t i) { return (hull[i].z - p.z) / (hull[i].t - p.t); };
  std::size_t lo = 0, hi = hull.size() - 1;
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (slope(mid) < slope(mid + 1)) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  return slope(lo);
}

struct LineSample {
  long line;
  HullPoint point;
};

// One direction over the whole buffer; writes the horizon angle (or the lowest angle when
// `negate`) for the window's cells into `plane` (window-sized, row-major).
//
// Parallel lines one cell apart cover the raster, sampled once per major step by linear
// interpolation between neighbouring cell centres (the surface the march reads). A cell's own
// ray runs between two lines at a constant offset. Its first kNearSteps crossings are read
// exactly, as the march does: near terrain moves the angle most, and there a line's sideways
// offset would look like a slope. Beyond them the cell, at its own height, takes its tangent to
// the hulls of the two lines beside it, the slopes interpolated by its offset; line samples join their
// hull only once they are more than kNearSteps behind the current step.
void sweep_direction(const Terrain& terrain, const float* transposed, const Window& window, double azimuth,
                     double curvature, bool negate, float* plane) {
  constexpr int kNearSteps = 8;
  const int W = terrain.width(), H = terrain.height();
  const Jacobian j = terrain.frame.at(terrain.origin_col + 0.5 * W, terrain.origin_row + 0.5 * H);
  double pc, pr;
  j.pixel_step_for_azimuth(azimuth, pc, pr);
  // Ground distance along the azimuth gained per column and per row step.
  const double se = std::sin(azimuth), cn = std::cos(azimuth);
  const double t_col = j.a * se + j.c * cn, t_row = j.b * se + j.d * cn;
  const double sign = negate ? -1.0 : 1.0;
  const double c = negate ? -curvature : curvature;
  const bool by_rows = std::abs(pr) >= std::abs(pc);
  const int major_n = by_rows ? H : W, minor_n = by_rows ? W : H;
  const double k = by_rows ? pc / pr : pr / pc;  // minor-axis drift of a line per major step
  const double t_major = by_rows ? t_row : t_col, t_minor = by_rows ? t_col : t_row;
  const bool ahead_is_low = by_rows ? pr < 0 : pc < 0;             // the viewer looks towards index 0
  const int toward = ahead_is_low ? -1 : 1;                        // major index change per step ahead
  const double t_step = std::abs(t_major) + k * toward * t_minor;  // along-ray distance per step
  const double k_step = k * toward;                                // minor drift per step ahead
  const long max_drift = static_cast<long>(std::ceil(std::abs(k) * (major_n - 1))) + 1;
  const long m_min = -max_drift, lines = minor_n + 2 * max_drift + 2;
  std::vector<std::vector<HullPoint>> hulls(static_cast<std::size_t>(lines));
  std::vector<std::vector<LineSample>> pending(kNearSteps + 1);  // samples not yet in a hull, by step
  // Lines that advance by columns read the transposed copy, so every line read is contiguous.
  const float* z = by_rows ? terrain.heights.data() : transposed;
  const std::ptrdiff_t minor_stride = 1, major_stride = by_rows ? W : H;
  auto height = [&](int major, double x) -> double {  // linear along the minor axis; x in range
    const float* zrow = z + major * major_stride;
    const int i0 = std::min(static_cast<int>(x), minor_n - 1);
    const double fx = x - i0;
    const double z0 = zrow[i0 * minor_stride];
    // x may exceed minor_n - 1 by a rounding error: never read past the row.
    return fx > 0.0 && i0 + 1 < minor_n ? z0 + fx * (zrow[(i0 + 1) * minor_stride] - z0) : z0;
  };

  for (int step = 0; step < major_n; ++step) {
    const int major = ahead_is_low ? step : major_n - 1 - step;
    const double shift = major * k;  // line m sits at minor position m + shift
    // Samples from more than kNearSteps steps back join their line's hull.
    for (const LineSample& s : pending[step % (kNearSteps + 1)]) {
      auto& hull = hulls[static_cast<std::size_t>(s.line - m_min)];
      const HullPoint& p = s.point;
      while (hull.size() >= 2) {
        const HullPoint& a = hull[hull.size() - 1];
        const HullPoint& b = hull[hull.size() - 2];
        if ((a.z - p.z) * (b.t - p.t) > (b.z - p.z) * (a.t - p.t)) break;
        hull.pop_back();
      }
      hull.push_back(p);
    }
    pending[step % (kNearSteps + 1)].clear();

    const float* zrow = z + major * major_stride;
    for (int minor = 0; minor < minor_n; ++minor) {
      const int col = by_rows ? minor : major, row = by_rows ? major : minor;
      const int wc = col - window.col0, wr = row - window.row0;
      if (wc < 0 || wr < 0 || wc >= window.cols || wr >= window.rows) continue;
      const float zc = zrow[minor * minor_stride];
      if (std::isnan(zc)) continue;
      const double t = major * t_major + minor * t_minor;
      double best = -std::numeric_limits<double>::infinity();
      // Near field: the cell's own ray, crossing by crossing.
      for (int s = 1; s <= kNearSteps; ++s) {
        const int mj = major + toward * s;
        const double x = minor + s * k_step;
        if (mj < 0 || mj >= major_n || x < 0.0 || x > minor_n - 1) break;
        const double zs = height(mj, x);
        if (std::isnan(zs)) continue;
        const double d = s * t_step;
        best = std::max(best, (sign * zs - sign * zc - c * d * d) / d);
      }
      // Far field: tangents to the two neighbouring lines' hulls.
      const double u = minor - shift;
      const long m0 = static_cast<long>(std::floor(u));
      const double f = u - m0;
      const HullPoint p{t, sign * zc - c * t * t};
      // Slopes, not angles, are interpolated: one arctangent per cell and direction.
      double far = 0.0, weight = 0.0;
      for (int side = 0; side < 2; ++side) {
        const double w = side == 0 ? 1.0 - f : f;
        const auto& hull = hulls[static_cast<std::size_t>(m0 + side - m_min)];
        if (w == 0.0 || hull.empty()) continue;
        far += w * (tangent_slope(hull, p) + 2.0 * c * t);
        weight += w;
      }
      if (weight > 0.0) best = std::max(best, far / weight);
      // Nothing ahead on either side: terrain beyond the raster does not occlude.
      const double angle = std::isinf(best) ? 0.0 : std::atan(best);
      plane[static_cast<std::size_t>(wr) * window.cols + wc] = static_cast<float>(sign * angle);
    }
    // This step's line samples wait kNearSteps steps before joining the hulls.
    auto& mine = pending[(step + kNearSteps + 1) % (kNearSteps + 1)];
    const long m_first = static_cast<long>(std::ceil(-shift)),
               m_last = static_cast<long>(std::floor(minor_n - 1 - shift));
    for (long m = m_first; m <= m_last; ++m) {
      const double x = m + shift;
      const double zs = height(major, x);
      if (std::isnan(zs)) continue;  // nodata never occludes
      const double t = major * t_major + x * t_minor;
      mine.push_back({m, {t, sign * zs - c * t * t}});
    }
  }
}

class SweepEngine final : public HorizonEngine {
 public:
  explicit SweepEngine(const HorizonParams& p) : p_(p) {
    if (p_.radius != 0.0) {
      throw Error(
          "--radius is not supported by --method sweep (the default), which is exact over the whole raster; use "
          "--method march or sampled for a limited radius");
    }
  }
  std::string_view name() const override { return "sweep"; }
  std::string_view citation() const override {
    return "upper convex hull sweep along digital lines (after Stewart 1998, IEEE TVCG 4(1)); exact, unlimited radius";
  }
  std::map<std::string, std::string> describe() const override {
    return {{"METHOD", "sweep"},
            {"DIRECTIONS", std::to_string(p_.directions)},
            {"RADIUS_M", "unlimited"},
            {"CURVATURE", p_.curvature},
            {"REFRACTION", std::to_string(p_.refraction)}};
  }
  double radius() const override { return std::numeric_limits<double>::infinity(); }
  void compute(const Terrain& terrain, const Window& window, HorizonField& out,
               ProgressCounter& progress) const override {
    out.resize(window.cols, window.rows, p_.directions, p_.lower);
    const Jacobian j = terrain.frame.at(terrain.origin_col, terrain.origin_row);
    const double extent = std::hypot(terrain.width() * std::hypot(j.a, j.c), terrain.height() * std::hypot(j.b, j.d));
    const double c = curvature_coefficient(p_, extent, terrain.frame.earth_radius());
    const int passes = p_.lower ? 2 : 1;
    const std::size_t cells = static_cast<std::size_t>(window.cols) * window.rows;
    const std::uint64_t per_pass = static_cast<std::uint64_t>(window.cells()) / std::max(1, p_.directions * passes);
    const int W = terrain.width(), H = terrain.height();
    std::vector<float> transposed(static_cast<std::size_t>(W) * H);
    for (int r = 0; r < H; ++r) {
      for (int col = 0; col < W; ++col) transposed[static_cast<std::size_t>(col) * H + r] = terrain.heights(col, r);
    }
    tbb::parallel_for(0, p_.directions * passes, [&](int task) {
      const int k = task % p_.directions;
      const bool negate = task >= p_.directions;
      std::vector<float> plane(cells, std::numeric_limits<float>::quiet_NaN());
      sweep_direction(terrain, transposed.data(), window, sector_azimuth(k, p_.directions), c, negate, plane.data());
      float* dst = negate ? out.lower.data() : out.upper.data();
      for (std::size_t i = 0; i < cells; ++i) dst[i * p_.directions + k] = plane[i];
      progress.advance(per_pass);
    });
  }

 private:
  HorizonParams p_;
};

}  // namespace

std::unique_ptr<HorizonEngine> make_sweep_engine(const HorizonParams& params) {
  return std::make_unique<SweepEngine>(params);
}

}  // namespace skyview::detail
