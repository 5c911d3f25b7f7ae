// Horizons in linear time per direction at unlimited radius. For one azimuth, parallel lines one
// cell apart cover the raster (sampled at every grid-line crossing). Walking a line from its
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
// Surface model: the ray-cast reference's mesh over cell centres, read where it can peak (every
// row and column crossing), as the march reads it. Exact along each cell's own ray for its first
// near_steps steps; beyond, a cell's slope interpolates its two neighbouring lines' tangents.
// With a radius, no hulls: every crossing within it along each cell's own ray (a vectorised march).
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "earth_curvature.h"
#include "fast_atan.h"
#include "methods.h"
#include "skyview/error.h"

namespace skyview::detail {
namespace {

struct HullPoint {
  double t, z;
};

// The tangent from p (nearer than every hull point) to an upper hull stored far-to-near is
// where slopes stop rising: slopes from an outside point along a convex chain are unimodal. Every
// hull point lies ahead of p (t - p.t has one sign), so slopes compare by cross products.
inline bool rises(const HullPoint& a, const HullPoint& b, const HullPoint& p) {
  return (a.z - p.z) * (b.t - p.t) < (b.z - p.z) * (a.t - p.t);
}

// One line's hull, the highest point it ever held (a bound on any tangent from below) and copies
// of its two nearest points: the tangent is the nearest point over flat ground (where curvature
// makes the profile a dome), and reading it here, from the array of lines that cells walk in
// order, saves a cache miss into each line's own vector.
struct LineHull {
  std::vector<HullPoint> points;
  double top = -std::numeric_limits<double>::infinity();
  HullPoint last{0, 0}, before_last{0, 0};
  mutable std::size_t hint = 0;  // the last tangent point found: pops only remove nearer points

  void push(const HullPoint& p) {
    while (points.size() >= 2) {
      const HullPoint& a = points[points.size() - 1];
      const HullPoint& b = points[points.size() - 2];
      if ((a.z - p.z) * (b.t - p.t) > (b.z - p.z) * (a.t - p.t)) break;
      points.pop_back();
    }
    if (!points.empty()) before_last = points.back();
    points.push_back(p);
    last = p;
    top = std::max(top, p.z);
  }

  // Slope of the tangent from p. Slopes rise along the hull up to the tangent point T and fall
  // after it, so "slope rises into i" holds exactly for i <= T. The nearest point is tried from
  // the copies (over flat ground with Earth curvature nearly every sample is a hull vertex, the
  // folded heights forming a dome, and the tangent is the nearest point); otherwise the search
  // gallops from this line's previous tangent point to bracket T, then bisects.
  double tangent_slope(const HullPoint& p) const {
    const std::size_t n = points.size();
    if (n == 1 || rises(before_last, last, p)) {
      hint = n - 1;
      return (last.z - p.z) / (last.t - p.t);
    }
    // The nearest point lies past the tangent. Start from the previous answer on this line (the
    // same distant peak, mostly) and gallop away from it to bracket the tangent, then bisect.
    const HullPoint* h = points.data();
    auto rises_into = [&](std::size_t i) { return i == 0 || rises(h[i - 1], h[i], p); };
    std::size_t lo, hi;  // rises_into(lo) holds, rises_into(hi) does not
    const std::size_t start = std::min(hint, n - 2);
    if (rises_into(start)) {
      lo = start, hi = n - 1;
      for (std::size_t step = 1; lo + step < hi; step *= 2) {
        if (!rises_into(lo + step)) {
          hi = lo + step;
          break;
        }
        lo += step;
      }
    } else {
      hi = start, lo = 0;
      for (std::size_t step = 1; step < hi; step *= 2) {
        if (rises_into(hi - step)) {
          lo = hi - step;
          break;
        }
        hi -= step;
        if (step >= hi) break;
      }
    }
    while (hi - lo > 1) {
      const std::size_t mid = lo + (hi - lo) / 2;
      (rises_into(mid) ? lo : hi) = mid;
    }
    hint = lo;
    return (h[lo].z - p.z) / (h[lo].t - p.t);
  }
};

// The grid line (integer) strictly between a and b, |a - b| <= 1, if any: where a straight path
// from a to b crosses it. The mesh every method shares peaks on grid lines, so a profile needs
// these crossings as well as those of the lines it steps along.
inline bool crossing_between(double a, double b, double& q) {
  q = a < b ? std::floor(b) : std::ceil(b);
  if (q == b) q += a < b ? -1.0 : 1.0;
  return a < b ? q > a : q < a;
}

struct LineSample {
  long line;
  HullPoint point;
};

// One direction over the whole buffer; writes the horizon angle (or the lowest angle when
// `negate`) for the window's cells into `field`, window-sized and row-major with `stride` floats
// per cell (the field's direction-interleaved layout; nodata cells are left alone).
//
// Parallel lines one cell apart cover the raster, sampled where they cross grid lines (each major
// step, read linearly between neighbouring cell centres, and each minor grid line between steps,
// read along it): the shared mesh peaks only there. A cell's own ray runs between two lines at a
// constant offset. Its first near_steps steps are read exactly, as the march does: near terrain
// moves the angle most, and there a line's sideways offset would look like a slope. Beyond them
// the cell, at its own height, takes its tangent to the hulls of the two lines beside it, the
// slopes interpolated by its offset; line samples join their hull only once they are more than
// near_steps behind the current step. The near field is a row of vector instructions per step,
// so 64 steps cost about what 8 did; they bring the city sample's p99 from 0.009 to 0.002.
//
// A row is done in passes over contiguous arrays: the near field one crossing at a time for the
// whole row (every cell of a row shares the crossing's fractional offset, so this vectorises),
// then the far field per cell, skipped where the hulls' highest points cannot beat the near
// field, then the arctangents.
// Compiled twice, for baseline x86-64 and for AVX2 (chosen at load time): the near field's row
// loops then run eight floats per instruction.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx2", "default")))
#endif
void sweep_direction(const Terrain& terrain, const float* transposed, const Window& window, double azimuth,
                     double curvature, bool negate, int near_steps, double radius, float* field,
                     std::size_t stride) {
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
  // Hull points are at least this far ahead of any cell that queries them.
  // With a search radius the sweep is a vectorised exhaustive march: every crossing within the
  // radius is read along the cell's own ray and no hull is kept.
  const bool limited = std::isfinite(radius);
  if (limited) near_steps = static_cast<int>(std::min<double>(major_n, std::floor(radius / t_step) + 1));
  // Hull points are at least far_gap ahead of any cell that queries them (the nearest is the minor
  // crossing between near_steps and near_steps + 1 steps ahead); where a sheared frame makes that
  // bound useless (far_gap <= 0), the far field is never skipped.
  const double far_gap = near_steps * t_step - std::abs(t_minor);
  const double inv_far_gap = far_gap > 0.0 ? 1.0 / far_gap : std::numeric_limits<double>::infinity();
  // Hulls and their pending samples; none with a radius.
  std::vector<LineHull> hulls(limited ? 0 : static_cast<std::size_t>(lines));
  std::vector<std::vector<LineSample>> pending(limited ? 0 : near_steps + 1);  // by step
  // Lines that advance by columns read the transposed copy, so every line read is contiguous.
  const float* z = by_rows ? terrain.heights.data() : transposed;
  const std::ptrdiff_t major_stride = by_rows ? W : H;
  auto height = [&](int major, double x) -> double {  // linear along the minor axis; x in range
    const float* zrow = z + major * major_stride;
    const int i0 = std::min(static_cast<int>(x), minor_n - 1);
    const double fx = x - i0;
    const double z0 = zrow[i0];
    // x may exceed minor_n - 1 by a rounding error: never read past the row.
    return fx > 0.0 && i0 + 1 < minor_n ? z0 + fx * (zrow[i0 + 1] - z0) : z0;
  };
  // The window's cells along the minor axis of a row.
  const int lo = std::max(0, by_rows ? window.col0 : window.row0);
  const int hi = std::min(minor_n, by_rows ? window.col0 + window.cols : window.row0 + window.rows);
  // Near-field slopes in float: four cells per SSE instruction; a float slope is good to 1e-7.
  std::vector<float> best(static_cast<std::size_t>(minor_n));
  const float sgn = static_cast<float>(sign);

  for (int step = 0; step < major_n; ++step) {
    const int major = ahead_is_low ? step : major_n - 1 - step;
    const double shift = major * k;  // line m sits at minor position m + shift
    // Samples from more than near_steps steps back join their line's hull.
    if (!limited) {
      auto& due = pending[step % (near_steps + 1)];
      for (const LineSample& s : due) hulls[static_cast<std::size_t>(s.line - m_min)].push(s.point);
      due.clear();
    }

    const int window_major = by_rows ? major - window.row0 : major - window.col0;
    const bool in_window = window_major >= 0 && window_major < (by_rows ? window.rows : window.cols);
    const float* zrow = z + major * major_stride;
    if (in_window && lo < hi) {
      // Near field: the cells' own rays, one crossing at a time for the whole row. NaN heights
      // lose every comparison, so nodata never occludes.
      std::fill(best.begin() + lo, best.begin() + hi, -std::numeric_limits<float>::infinity());
      for (int s = 1; s <= near_steps; ++s) {
        const int mj = major + toward * s;
        if (mj < 0 || mj >= major_n) break;
        const double off = s * k_step;
        const int i_off = static_cast<int>(std::floor(off));
        const double f = off - i_off;
        // Cells whose crossing stays inside the row: 0 <= minor + off <= minor_n - 1.
        const int a = std::max(lo, static_cast<int>(std::ceil(-off)));
        const int b = std::min(hi, static_cast<int>(std::floor(minor_n - 1 - off)) + 1);
        const float* zs = z + mj * major_stride + i_off;
        const double d = s * t_step;
        float* bst = best.data();
        // Beyond the radius the row crossing is skipped; the column crossing before it may count.
        if (!limited || d <= radius) {
          const float inv_d = static_cast<float>(1.0 / d), drop = static_cast<float>(c * d), ff = static_cast<float>(f);
          if (f > 0.0) {
            const int b1 = std::min(b, minor_n - 1 - i_off);  // the right neighbour exists
            for (int m = a; m < b1; ++m) {
              const float zi = zs[m] + ff * (zs[m + 1] - zs[m]);
              const float v = sgn * (zi - zrow[m]) * inv_d - drop;
              bst[m] = v > bst[m] ? v : bst[m];
            }
            for (int m = std::max(a, b1); m < b; ++m) {
              const float v = sgn * (zs[m] - zrow[m]) * inv_d - drop;
              bst[m] = v > bst[m] ? v : bst[m];
            }
          } else {
            for (int m = a; m < b; ++m) {
              const float v = sgn * (zs[m] - zrow[m]) * inv_d - drop;
              bst[m] = v > bst[m] ? v : bst[m];
            }
          }
        }
        // The minor grid line crossed between crossings s - 1 and s, read along it.
        double q;
        if (crossing_between((s - 1) * k_step, off, q) &&
            (!limited || (s - 1 + (q - (s - 1) * k_step) / k_step) * t_step <= radius)) {
          const double lambda = (q - (s - 1) * k_step) / k_step;
          const int qi = static_cast<int>(q);
          const int qa = std::max(lo, -qi), qb = std::min(hi, minor_n - qi);
          const float* z0 = z + (mj - toward) * major_stride + qi;
          const float* z1 = z + mj * major_stride + qi;
          const double dq = (s - 1 + lambda) * t_step;
          const float inv_dq = static_cast<float>(1.0 / dq), drop_q = static_cast<float>(c * dq),
                      lf = static_cast<float>(lambda);
          for (int m = qa; m < qb; ++m) {
            const float zi = z0[m] + lf * (z1[m] - z0[m]);
            const float v = sgn * (zi - zrow[m]) * inv_dq - drop_q;
            bst[m] = v > bst[m] ? v : bst[m];
          }
        }
      }
      // Far field: tangents to the two neighbouring lines' hulls.
      for (int minor = limited ? hi : lo; minor < hi; ++minor) {
        const float zc = zrow[minor];
        if (std::isnan(zc)) continue;
        const double t = major * t_major + minor * t_minor;
        const double u = minor - shift;
        const long m0 = static_cast<long>(std::floor(u));
        const double fu = u - m0;
        const HullPoint p{t, sign * zc - c * t * t};
        LineHull& h0 = hulls[static_cast<std::size_t>(m0 - m_min)];
        LineHull& h1 = hulls[static_cast<std::size_t>(m0 + 1 - m_min)];
        double near = best[static_cast<std::size_t>(minor)];
        // The far slope of a line is at most its highest point over the smallest gap.
        const double rise = std::max(h0.top, h1.top) - p.z;
        const double bound = (rise > 0.0 ? rise * inv_far_gap : 0.0) + 2.0 * c * t;
        if (near >= bound) continue;
        // Slopes, not angles, are interpolated: one arctangent per cell and direction.
        double far = 0.0, weight = 0.0;
        if (fu < 1.0 && !h0.points.empty()) {
          far += (1.0 - fu) * (h0.tangent_slope(p) + 2.0 * c * t);
          weight += 1.0 - fu;
        }
        if (fu > 0.0 && !h1.points.empty()) {
          far += fu * (h1.tangent_slope(p) + 2.0 * c * t);
          weight += fu;
        }
        if (weight > 0.0) best[static_cast<std::size_t>(minor)] = static_cast<float>(std::max(near, far / weight));
      }
      // Angles; nothing ahead on either side (-inf) means open: terrain beyond the raster does
      // not occlude. Written straight into the field: a separate plane and an interleaving pass
      // cost a page-faulted buffer per direction and a second strided walk.
      const std::size_t step_out = stride * (by_rows ? 1 : static_cast<std::size_t>(window.cols));
      float* out = field + stride * (by_rows ? static_cast<std::size_t>(major - window.row0) * window.cols +
                                                   static_cast<std::size_t>(lo - window.col0)
                                             : static_cast<std::size_t>(lo - window.row0) * window.cols +
                                                   static_cast<std::size_t>(major - window.col0));
      for (int minor = lo; minor < hi; ++minor, out += step_out) {
        const double v = best[static_cast<std::size_t>(minor)];
        const float angle =
            static_cast<float>(v == -std::numeric_limits<double>::infinity() ? 0.0 : sign * fast_atan(v));
        if (!std::isnan(zrow[minor])) *out = angle;
      }
    }
    if (limited) continue;  // no hulls within a radius
    // This step's line samples wait near_steps steps before joining the hulls.
    auto& mine = pending[(step + near_steps + 1) % (near_steps + 1)];
    // First each line's crossing of a minor grid line since the previous (farther) step: every
    // line has it at the same fraction of the step. It joins the hulls with the previous step's
    // samples, one step before this step's: the near field reads crossings only up to near_steps
    // steps ahead, and the one just beyond must be in a hull by then.
    const double base = std::floor(shift), fs = shift - base;
    double q;
    if (step > 0 && crossing_between(fs, fs + k_step, q)) {
      auto& earlier = pending[(step - 1) % (near_steps + 1)];
      const double lambda = (q - fs) / k_step;
      const float* z0 = z + major * major_stride;
      const float* z1 = z + (major + toward) * major_stride;
      const long qb = static_cast<long>(q + base);  // line m crosses at minor m + qb
      const long m_a = std::max(-qb, m_min + 1), m_b = std::min<long>(minor_n - 1 - qb, m_min + lines - 2);
      for (long m = m_a; m <= m_b; ++m) {
        const long x = m + qb;
        const double zs = z0[x] + lambda * (static_cast<double>(z1[x]) - z0[x]);
        if (std::isnan(zs)) continue;
        const double t = (major + toward * lambda) * t_major + x * t_minor;
        earlier.push_back({m, {t, sign * zs - c * t * t}});
      }
    }
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
    if (p_.samples == 0) p_.samples = 64;
    if (p_.samples < 1 || p_.samples > 4096) throw Error("--samples (exact near steps) must be 1 to 4096 for sweep");
    if (p_.radius < 0.0 || !std::isfinite(p_.radius)) throw Error("--radius must be positive (or 0 for unlimited)");
  }
  std::string_view name() const override { return "sweep"; }
  std::string_view citation() const override {
    return "upper convex hull sweep along digital lines (after Stewart 1998, IEEE TVCG 4(1)); unlimited radius, or "
           "every crossing within --radius";
  }
  std::map<std::string, std::string> describe() const override {
    return {{"METHOD", "sweep"},
            {"DIRECTIONS", std::to_string(p_.directions)},
            {"RADIUS_M", p_.radius > 0 ? std::to_string(p_.radius) : "unlimited"},
            {"NEAR_STEPS", p_.radius > 0 ? "all within the radius" : std::to_string(p_.samples)},
            {"CURVATURE", p_.curvature},
            {"REFRACTION", std::to_string(p_.refraction)}};
  }
  double radius() const override { return p_.radius > 0 ? p_.radius : std::numeric_limits<double>::infinity(); }
  void compute(const Terrain& terrain, const Window& window, HorizonField& out,
               ProgressCounter& progress) const override {
    out.resize(window.cols, window.rows, p_.directions, p_.lower);
    const Jacobian j = terrain.frame.at(terrain.origin_col, terrain.origin_row);
    const double extent = std::hypot(terrain.width() * std::hypot(j.a, j.c), terrain.height() * std::hypot(j.b, j.d));
    const double c = curvature_coefficient(p_, p_.radius > 0 ? p_.radius : extent, terrain.frame.earth_radius());
    const int passes = p_.lower ? 2 : 1;
    const std::uint64_t per_pass = static_cast<std::uint64_t>(window.cells()) / std::max(1, p_.directions * passes);
    const int W = terrain.width(), H = terrain.height();
    std::vector<float> transposed(static_cast<std::size_t>(W) * H);
    for (int r = 0; r < H; ++r) {
      for (int col = 0; col < W; ++col) transposed[static_cast<std::size_t>(col) * H + r] = terrain.heights(col, r);
    }
    tbb::parallel_for(0, p_.directions * passes, [&](int task) {
      const int k = task % p_.directions;
      const bool negate = task >= p_.directions;
      float* field = (negate ? out.lower.data() : out.upper.data()) + k;
      sweep_direction(terrain, transposed.data(), window, sector_azimuth(k, p_.directions), c, negate, p_.samples,
                      radius(), field, static_cast<std::size_t>(p_.directions));
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
