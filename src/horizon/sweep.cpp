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

// One direction over the whole buffer; writes the horizon angle (or the lowest angle when
// `negate`) for the window's cells into `plane` (window-sized, row-major).
//
// Lines are exact straight lines one cell apart across the minor axis, sampled once per major
// step by linear interpolation between the two neighbouring cell centres (the surface the march
// reads). Each sample's horizon is its tangent to the hull of the samples ahead, found as the
// sample is pushed; a cell takes the horizons of the two line samples beside it, interpolated
// by its offset, which is exact on planes and exact for cells a line passes through.
void sweep_direction(const Terrain& terrain, const Window& window, double azimuth, double curvature, bool negate,
                     float* plane) {
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
  const bool ahead_is_low = by_rows ? pr < 0 : pc < 0;  // the viewer looks towards index 0
  const long max_drift = static_cast<long>(std::ceil(std::abs(k) * (major_n - 1))) + 1;
  const long m_min = -max_drift, lines = minor_n + 2 * max_drift + 2;
  std::vector<std::vector<HullPoint>> hulls(static_cast<std::size_t>(lines));
  // Horizon of each line's sample at the current major step; NaN where the line has none.
  std::vector<double> line_angle(static_cast<std::size_t>(lines), std::numeric_limits<double>::quiet_NaN());
  const float* z = terrain.heights.data();
  const std::ptrdiff_t minor_stride = by_rows ? 1 : W, major_stride = by_rows ? W : 1;

  for (int step = 0; step < major_n; ++step) {
    const int major = ahead_is_low ? step : major_n - 1 - step;
    const double shift = major * k;  // line m sits at minor position m + shift
    const float* zrow = z + major * major_stride;
    const long m_first = static_cast<long>(std::ceil(-shift) - 1),
               m_last = static_cast<long>(std::floor(minor_n - 1 - shift) + 1);
    for (long m = m_first; m <= m_last; ++m) {
      double& angle = line_angle[static_cast<std::size_t>(m - m_min)];
      angle = std::numeric_limits<double>::quiet_NaN();
      const double x = m + shift;
      if (x < 0.0 || x > minor_n - 1) continue;
      const int i0 = std::min(static_cast<int>(x), minor_n - 1);
      const double fx = x - i0;
      const double z0 = zrow[i0 * minor_stride];
      const double zs = fx > 0.0 ? z0 + fx * (zrow[(i0 + 1) * minor_stride] - z0) : z0;
      if (std::isnan(zs)) continue;  // nodata neither occludes nor has a horizon
      const double t = major * t_major + x * t_minor;
      const HullPoint p{t, sign * zs - c * t * t};
      auto& hull = hulls[static_cast<std::size_t>(m - m_min)];
      // Pop hull points that lie on or below the chord from p to the point after them; the
      // point left on top is p's tangent point.
      while (hull.size() >= 2) {
        const HullPoint& a = hull[hull.size() - 1];
        const HullPoint& b = hull[hull.size() - 2];
        if ((a.z - p.z) * (b.t - p.t) > (b.z - p.z) * (a.t - p.t)) break;
        hull.pop_back();
      }
      // Nothing ahead: terrain beyond the raster does not occlude (angle 0).
      angle = hull.empty() ? 0.0 : std::atan((hull.back().z - p.z) / (hull.back().t - p.t) + 2.0 * c * t);
      hull.push_back(p);
    }
    for (int minor = 0; minor < minor_n; ++minor) {
      const int col = by_rows ? minor : major, row = by_rows ? major : minor;
      const int wc = col - window.col0, wr = row - window.row0;
      if (wc < 0 || wr < 0 || wc >= window.cols || wr >= window.rows) continue;
      if (std::isnan(zrow[minor * minor_stride])) continue;
      const double u = minor - shift;
      const long m0 = static_cast<long>(std::floor(u));
      const double f = u - m0;
      const double a0 = line_angle[static_cast<std::size_t>(m0 - m_min)];
      const double a1 = line_angle[static_cast<std::size_t>(m0 + 1 - m_min)];
      // A line without a sample here (nodata) gives way to the other one.
      double angle = 0.0;
      if (std::isnan(a0)) {
        angle = std::isnan(a1) ? 0.0 : a1;
      } else if (std::isnan(a1) || f == 0.0) {
        angle = a0;
      } else {
        angle = (1.0 - f) * a0 + f * a1;
      }
      plane[static_cast<std::size_t>(wr) * window.cols + wc] = static_cast<float>(sign * angle);
    }
  }
}

class SweepEngine final : public HorizonEngine {
 public:
  explicit SweepEngine(const HorizonParams& p) : p_(p) {
    if (p_.radius != 0.0) {
      throw Error("--radius is not supported by --method sweep, which is exact over the whole raster");
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
    tbb::parallel_for(0, p_.directions * passes, [&](int task) {
      const int k = task % p_.directions;
      const bool negate = task >= p_.directions;
      std::vector<float> plane(cells, std::numeric_limits<float>::quiet_NaN());
      sweep_direction(terrain, window, sector_azimuth(k, p_.directions), c, negate, plane.data());
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
