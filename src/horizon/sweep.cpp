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
// near_steps steps (default 64); beyond, a cell's slope is the nearer line's tangent (far_lines 1,
// the default), or interpolates its two neighbouring lines' tangents (far_lines 2): two queries
// instead of one, about as accurate as one line with twice the near steps and about 1.3x slower at
// 4000 x 4000 (measured in docs/benchmarks.md). Along the grid's axes and
// diagonals the lines run through cell centres, a cell's own ray is its line, and the issue's
// design is exact as it stands: each cell is pushed onto its line's hull and its horizon is the
// tangent found there (no near field, no query; about 2.8x faster per direction at 4000 x 4000).
// Along half slopes (k = ±1/2, --azimuths grid-lines) lines half a cell apart do the same at
// twice the pushes (cells_on_lines).
// With a radius, no hulls: every crossing within it along each cell's own ray (a vectorised march).
//
// Memory layout, the cost that matters: lines are walked in bands of kBand neighbouring lines
// from the far end to the near end. A band's hulls share one arena and its cells and line samples
// lie in a strip kBand + 1 cells wide (near-field reads reach near_steps |k| cells beyond), so the
// whole walk stays in the caches. Walking every line of the raster one row at a time instead
// loaded each line's hull from memory at every row (a cache miss per cell and direction: 2.8x
// slower at 4000 x 4000).
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "earth_curvature.h"
#include "fast_atan.h"
#include "methods.h"
#include "skyview/core/error.h"
#include "skyview/core/large_pages.h"
#include "skyview/core/number_text.h"

namespace skyview::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct HullPoint {
  double t, z;
};

// The tangent from p (nearer than every hull point) to an upper hull stored far-to-near is
// where slopes stop rising: slopes from an outside point along a convex chain are unimodal. Every
// hull point lies ahead of p (t - p.t has one sign), so slopes compare by cross products.
inline bool rises(const HullPoint& a, const HullPoint& b, const HullPoint& p) {
  return (a.z - p.z) * (b.t - p.t) < (b.z - p.z) * (a.t - p.t);
}

// One line's upper hull in a slice of its band's arena, the highest point it ever held (a bound on
// any tangent from below) and copies of its two nearest points: the tangent is the nearest point
// over flat ground (where curvature makes the profile a dome), and the copies sit in the small
// array of lines that the cells read in turn.
struct LineHull {
  HullPoint* points = nullptr;
  std::size_t n = 0;
  double top = -kInf;
  HullPoint last{0, 0}, before_last{0, 0};
  double first_t = 0;  // position of the farthest point (pops stop before it)
  // The last tangent point found for the strip on either side of the line (cells there differ
  // in height, so their tangents differ); pops only remove nearer points.
  std::size_t hint[2] = {0, 0};

  void clear() {
    n = 0;
    top = -kInf;
    hint[0] = hint[1] = 0;
  }

  // `same`: a sample nearer than this to the nearest point (a minor crossing that rounding put on
  // a row crossing) would make two points of equal slope from every viewer, and the tangent
  // search needs slopes strictly rising up to the tangent: the higher of the two stays.
  // Returns p's tangent point on the hull before it (the point it now lies behind: the pops remove
  // exactly the points under the slope to their farther neighbour); null if none or merged.
  // Without kCopies the copies and the top that far-field queries read are not kept: lines that
  // hold every cell (cells_on_lines) are never queried.
  template <bool kCopies = true>
  const HullPoint* push(const HullPoint& p, double same) {
    if (n > 0 && points[n - 1].t - p.t < same) {
      if (p.z <= points[n - 1].z) return nullptr;
      --n;
    }
    while (n >= 2) {
      const HullPoint& a = points[n - 1];
      const HullPoint& b = points[n - 2];
      if ((a.z - p.z) * (b.t - p.t) > (b.z - p.z) * (a.t - p.t)) break;
      --n;
    }
    if constexpr (kCopies) {
      if (n > 0) before_last = points[n - 1];
      if (n == 0) first_t = p.t;
    }
    points[n++] = p;
    if constexpr (kCopies) {
      last = p;
      top = std::max(top, p.z);
    }
    return n >= 2 ? &points[n - 2] : nullptr;
  }

  // Whether no point of the hull rises above slope s from p, judged from the copies alone: the
  // hull is concave, so beyond its nearest point it lies under the line through its two nearest
  // points and under its highest point; the slope from p to that envelope is monotone on each of
  // its two pieces, so their ends bound it.
  bool under_slope(const HullPoint& p, double s) const {
    if (n == 0) return true;
    auto under = [&](double qt, double qz) { return qz - p.z <= s * (qt - p.t); };
    if (!under(last.t, last.z)) return false;
    if (n == 1) return true;
    const double dt = before_last.t - last.t, dz = before_last.z - last.z;
    if (dz <= 0.0) return under(first_t, last.z);
    const double reach = last.t + (top - last.z) * (dt / dz);  // where the line meets the top
    return (reach >= first_t || under(reach, top)) && under(first_t, top);
  }

  // Slope of the tangent from p. Slopes rise along the hull up to the tangent point T and fall
  // after it, so "slope rises into i" holds exactly for i <= T. The nearest point is tried from
  // the copies; otherwise the search gallops from this line's previous tangent point (the same
  // distant peak, mostly) to bracket T, then bisects.
  double tangent_slope(const HullPoint& p, int side) {
    std::size_t& hint = this->hint[side];
    if (n == 1 || rises(before_last, last, p)) {
      hint = n - 1;
      return (last.z - p.z) / (last.t - p.t);
    }
    const HullPoint* h = points;
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

// One direction's lines in raster terms. Lines advance along the major axis (rows when the
// direction is nearer north-south than east-west), drifting k cells along the minor axis per
// major index: line m sits at minor position m + major * k. Steps count from the far end of the
// walk (step 0) towards the viewer.
struct SweepGeometry {
  bool by_rows = true;
  int major_n = 0, minor_n = 0;
  double k = 0, t_major = 0, t_minor = 0;  // ground distance along the azimuth per major and minor index
  int toward = 1;                          // major index change per step ahead (away from the viewer)
  double t_step = 0;                       // along-ray distance per step
  double k_step = 0;                       // minor drift per step ahead
  const float* z = nullptr;                // heights, minor axis contiguous (the transposed copy for columns)
  std::ptrdiff_t major_stride = 0;

  int major_at(int step) const { return toward < 0 ? step : major_n - 1 - step; }
  int step_at(int major) const { return toward < 0 ? major : major_n - 1 - major; }
  // The window's cells as major [major_lo, major_hi) by minor [minor_lo, minor_hi), clipped.
  void window_span(const Window& w, int& major_lo, int& major_hi, int& minor_lo, int& minor_hi) const {
    major_lo = std::max(0, by_rows ? w.row0 : w.col0);
    major_hi = std::min(major_n, by_rows ? w.row0 + w.rows : w.col0 + w.cols);
    minor_lo = std::max(0, by_rows ? w.col0 : w.row0);
    minor_hi = std::min(minor_n, by_rows ? w.col0 + w.cols : w.row0 + w.rows);
  }
  const float* row(int major) const { return z + major * major_stride; }
};

SweepGeometry make_geometry(const Terrain& terrain, const float* transposed, double azimuth) {
  SweepGeometry g;
  const int W = terrain.width(), H = terrain.height();
  // Every tile and block of a raster gets the same lines; and a direction set rotated to grid north
  // (direction_set_rotation) puts its axes exactly on rows and columns.
  const Jacobian j = raster_centre_jacobian(terrain);
  double pc, pr;
  j.pixel_step_for_azimuth(azimuth, pc, pr);
  const double se = std::sin(azimuth), cn = std::cos(azimuth);
  const double t_col = j.a * se + j.c * cn, t_row = j.b * se + j.d * cn;
  g.by_rows = std::abs(pr) >= std::abs(pc);
  g.major_n = g.by_rows ? H : W;
  g.minor_n = g.by_rows ? W : H;
  g.k = g.by_rows ? pc / pr : pr / pc;
  // Along an axis or a diagonal of square cells, keep lines exactly on cell centres and corners:
  // a drift of 1 - 1e-16 per step would put a minor crossing a rounding error from every sample.
  // A drift off that adds up to under 1e-4 cell over the whole raster is such a residue, not a
  // direction (the grid diagonals of a set rotated to grid north come out 1e-9 off, from the
  // frame's numerical Jacobian), and far below what one Jacobian for the raster already neglects.
  const double residue = 1e-4 / std::max(1, g.by_rows ? terrain.raster_height() : terrain.raster_width());
  if (std::abs(g.k) < residue) g.k = 0.0;
  if (std::abs(std::abs(g.k) - 1.0) < residue) g.k = std::copysign(1.0, g.k);
  // Half slopes: the grid lines' (1, 2) steps, or a uniform set's 45° on cells twice as long as wide.
  if (std::abs(std::abs(g.k) - 0.5) < residue) g.k = std::copysign(0.5, g.k);
  g.t_major = g.by_rows ? t_row : t_col;
  g.t_minor = g.by_rows ? t_col : t_row;
  g.toward = (g.by_rows ? pr < 0 : pc < 0) ? -1 : 1;  // the viewer looks towards index 0 when -1
  g.t_step = std::abs(g.t_major) + g.k * g.toward * g.t_minor;
  g.k_step = g.k * g.toward;
  // Lines that advance by columns read the transposed copy, so every line read is contiguous.
  g.z = g.by_rows ? terrain.heights.data() : transposed;
  g.major_stride = g.by_rows ? W : H;
  return g;
}

// One crossing of every cell's own ray, at the same offset from each cell (so a row of cells
// reads it in one vector loop): the height p0[m] + w (p1[m] - p0[m]), where p0 and p1 are rows
// `ahead0` and `ahead1` steps ahead shifted by col0 and col1 along the minor axis. Either two
// neighbours along a row (a major-step crossing) or two rows at one minor index (the minor grid
// line crossed between two steps).
struct NearCrossing {
  int ahead0, col0, ahead1, col1;
  float w;
  float scale;  // 1 / distance
  float drop;   // curvature drop over the distance, in slope units
};

// The first near_steps steps of a cell's own ray, and every minor grid line they cross, within
// `radius`; in order of distance.
std::vector<NearCrossing> near_crossings(const SweepGeometry& g, int near_steps, double radius, double c) {
  std::vector<NearCrossing> out;
  for (int s = 1; s <= near_steps; ++s) {
    const double off = s * g.k_step;
    double q;
    if (crossing_between((s - 1) * g.k_step, off, q)) {
      const double lambda = (q - (s - 1) * g.k_step) / g.k_step;
      const double d = (s - 1 + lambda) * g.t_step;
      const int qi = static_cast<int>(q);
      if (d <= radius)
        out.push_back(
            {s - 1, qi, s, qi, static_cast<float>(lambda), static_cast<float>(1.0 / d), static_cast<float>(c * d)});
    }
    const double d = s * g.t_step;
    const int i_off = static_cast<int>(std::floor(off));
    const double f = off - i_off;
    // With no fraction the neighbour is not read: a NaN there would poison w * (p1 - p0).
    if (d <= radius)
      out.push_back({s, i_off, s, f > 0.0 ? i_off + 1 : i_off, static_cast<float>(f), static_cast<float>(1.0 / d),
                     static_cast<float>(c * d)});
  }
  return out;
}

// Eight floats, the width of an AVX2 register (GCC's vector extension: two SSE registers in the
// baseline build).
using Floats8 = float __attribute__((vector_size(32)));

// (By reference: returning a vector type by value changes the ABI between the two builds.)
inline void load8(Floats8& v, const float* p) { std::memcpy(&v, p, sizeof v); }

// Near field of the cells [a, b) of the row at `major`: the highest slope of each cell's own ray
// over the crossings, into best[a, b) (indexed by minor), and with kLowest minus the lowest into
// lowest[a, b): the lowest angle's slope, which negated heights would give bit for bit (float
// rounding is symmetric), from the same loads. NaN heights lose every comparison, so nodata never
// occludes. Float slopes are good to 1e-7. Blocks of 32 cells that read every crossing inside the
// raster keep their heights and slopes in registers over all crossings (a crossing costs two loads
// and six or seven operations per eight cells); the rest, near the raster's sides, goes crossing by
// crossing. Inlined into near_field, which is compiled for baseline x86-64 and for AVX2.
template <bool kLowest>
__attribute__((always_inline)) inline void near_extremes(const SweepGeometry& g,
                                                         const std::vector<NearCrossing>& crossings, int major, int a,
                                                         int b, float* best, float* lowest) {
  constexpr float kNone = -std::numeric_limits<float>::infinity();
  std::fill(best + a, best + b, kNone);
  if (kLowest) std::fill(lowest + a, lowest + b, -kNone);  // the smallest slope until negated below
  const float* zrow = g.row(major);
  // The crossings whose rows exist from this row (they come in order of distance), and the cells
  // that read all of them inside the row.
  std::size_t count = 0;
  int all_lo = a, all_hi = b;
  for (const NearCrossing& x : crossings) {
    const int r1 = major + g.toward * x.ahead1;
    if (r1 < 0 || r1 >= g.major_n) break;
    all_lo = std::max({all_lo, -x.col0, -x.col1});
    all_hi = std::min({all_hi, g.minor_n - x.col0, g.minor_n - x.col1});
    ++count;
  }
  constexpr int kBlock = 32;
  const int blocks = all_hi > all_lo ? (all_hi - all_lo) / kBlock : 0;
  for (int block = 0; block < blocks; ++block) {
    const int m = all_lo + block * kBlock;
    Floats8 zc[4], top[4], bottom[4];
    for (int j = 0; j < 4; ++j) {
      load8(zc[j], zrow + m + 8 * j);
      top[j] = Floats8{} + kNone;
      bottom[j] = Floats8{} - kNone;
    }
    for (std::size_t i = 0; i < count; ++i) {
      const NearCrossing& x = crossings[i];
      const float* z0 = g.row(major + g.toward * x.ahead0) + (x.col0 + m);  // in the row: m >= -col0
      const float* z1 = g.row(major + g.toward * x.ahead1) + (x.col1 + m);
      const float w = x.w, scale = x.scale, drop = x.drop;
#pragma GCC unroll 4
      for (int j = 0; j < 4; ++j) {
        Floats8 h0, h1;
        load8(h0, z0 + 8 * j);
        load8(h1, z1 + 8 * j);
        const Floats8 v = (h0 + w * (h1 - h0) - zc[j]) * scale - drop;
        top[j] = v > top[j] ? v : top[j];
        if (kLowest) bottom[j] = v < bottom[j] ? v : bottom[j];
      }
    }
    std::memcpy(best + m, top, sizeof top);
    if (kLowest) {
      for (int j = 0; j < 4; ++j) bottom[j] = -bottom[j];
      std::memcpy(lowest + m, bottom, sizeof bottom);
    }
  }
  // The cells left over: crossing by crossing, each within the cells that read it inside the row.
  auto by_crossing = [&](int lo, int hi) {
    for (std::size_t i = 0; i < count && lo < hi; ++i) {
      const NearCrossing& x = crossings[i];
      const int ma = std::max({lo, -x.col0, -x.col1});
      const int mb = std::min({hi, g.minor_n - x.col0, g.minor_n - x.col1});
      const float* z0 = g.row(major + g.toward * x.ahead0);
      const float* z1 = g.row(major + g.toward * x.ahead1);
      const int c0 = x.col0, c1 = x.col1;
      const float w = x.w, scale = x.scale, drop = x.drop;
      for (int m = ma; m < mb; ++m) {
        const float zi = z0[m + c0] + w * (z1[m + c1] - z0[m + c0]);
        const float v = (zi - zrow[m]) * scale - drop;
        best[m] = v > best[m] ? v : best[m];
        if (kLowest) lowest[m] = v < lowest[m] ? v : lowest[m];
      }
    }
    if (kLowest) {
      for (int m = lo; m < hi; ++m) lowest[m] = -lowest[m];
    }
  };
  if (blocks > 0) {
    by_crossing(a, all_lo);
    by_crossing(all_lo + blocks * kBlock, b);
  } else {
    by_crossing(a, b);
  }
}

// The near field of near_extremes, for the horizon alone or (`lowest` not null) with the lowest
// angle.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx2", "default")))
#endif
void near_field(const SweepGeometry& g, const std::vector<NearCrossing>& crossings, int major, int a, int b,
                float* best, float* lowest) {
  if (lowest)
    near_extremes<true>(g, crossings, major, a, b, best, lowest);
  else
    near_extremes<false>(g, crossings, major, a, b, best, lowest);
}

// Angles of the cells [a, b) of the row at `major` into the direction's plane of the field
// (window-sized, row-major), turned in place in `best` first so that the arctangents run as one
// vector loop. Nothing ahead on either side (-inf) means open: terrain beyond the raster does not
// occlude. Nodata cells get NaN, as the field starts.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx2", "default")))
#endif
void write_angles(const SweepGeometry& g, const Window& window, int major, int a, int b, float* best, double sign,
                  float* plane) {
  const float* zrow = g.row(major);
  for (int m = a; m < b; ++m) {
    const double v = best[m];
    const double atan_v = sign * fast_atan(v);  // computed for every cell: no branch in the loop
    const float angle = static_cast<float>(v == -kInf ? 0.0 : atan_v);
    best[m] = std::isnan(zrow[m]) ? std::numeric_limits<float>::quiet_NaN() : angle;
  }
  if (g.by_rows) {
    float* out = plane + static_cast<std::size_t>(major - window.row0) * window.cols + (a - window.col0);
    std::memcpy(out, best + a, sizeof(float) * static_cast<std::size_t>(b - a));
  } else {
    float* out = plane + static_cast<std::size_t>(a - window.row0) * window.cols + (major - window.col0);
    for (int m = a; m < b; ++m, out += window.cols) *out = best[m];
  }
}

// Where each step's lines are: their shift along the minor axis, and the minor grid line they all
// cross between the previous (farther) step and this one, at the same fraction of the step.
struct StepLines {
  int major = 0;
  double shift = 0;  // line m sits at minor m + shift
  // Cell i lies between lines i + cell_line and i + cell_line + 1, `offset` of a cell from the
  // first: the same for every cell of the row (exact: -shift minus its floor has no rounding).
  long cell_line = 0;
  double offset = 0;
  // The first cell whose strip starts at line m or later.
  long first_cell(long m) const { return m - cell_line; }
  bool crossing = false;
  long cross_at = 0;  // line m crosses its minor grid line at minor m + cross_at
  double lambda = 0;  // ... this fraction of the step from this row towards the farther one
};

std::vector<StepLines> step_lines(const SweepGeometry& g) {
  std::vector<StepLines> out(static_cast<std::size_t>(g.major_n));
  for (int step = 0; step < g.major_n; ++step) {
    StepLines& s = out[static_cast<std::size_t>(step)];
    s.major = g.major_at(step);
    s.shift = s.major * g.k;
    s.cell_line = static_cast<long>(std::floor(-s.shift));
    s.offset = -s.shift - std::floor(-s.shift);
    const double base = std::floor(s.shift), fs = s.shift - base;
    double q;
    s.crossing = step > 0 && crossing_between(fs, fs + g.k_step, q);
    if (s.crossing) {
      s.cross_at = static_cast<long>(q + base);
      s.lambda = (q - fs) / g.k_step;
    }
  }
  return out;
}

// Cells' strips per band: a band keeps kBand + 1 hulls, or twice the lines on half slopes
// (DirectionSweep::band_lines).
constexpr int kBand = 256;

// Scratch for one step's samples of a band's lines (row crossings and minor grid crossings): the
// heights as read, then as one walk's hulls hold them.
struct BandSamples {
  double row_t[kBand + 1], row_z[kBand + 1], cross_t[kBand + 1], cross_z[kBand + 1];
  double row_f[kBand + 1], cross_f[kBand + 1];
};

// One of the walks a band makes at once over the same lines: the horizon (heights as they are) or
// the lowest angle (heights negated, so the lowest terrain is the highest). Each keeps its own
// hulls, slopes and output plane; they share the line samples and the near field's
// crossings, which are about 40% of a walk's time.
struct Walk {
  double sign = 1, c = 0;  // heights' sign, and the curvature coefficient in that sign
  float* plane = nullptr;  // the direction's plane of the field, window-sized
  // A height at position t along the ray, negated for the lowest angle and folded for Earth
  // curvature (see the top of this file): what the hulls hold.
  double folded(double t, double z) const { return sign * z - c * t * t; }
};

// A walk's state in the band being walked.
struct WalkState {
  LineHull* hulls = nullptr;  // band_lines() + 1, in their own arena
  float* best = nullptr;      // row-sized scratch of slopes
};

// One direction, shared by its bands. Cells between lines m and m + 1 (one per step: the strip is a
// cell wide) take their far field from those two lines' hulls; a band walks kBand neighbouring
// strips together so that the near field still runs as a vector loop over kBand cells of a row.
class DirectionSweep {
 public:
  static constexpr int kMaxWalks = 2;

  // `lower_plane` null: the horizon only.
  DirectionSweep(const SweepGeometry& g, const Window& window, int near_steps, int far_lines, bool early_exit,
                 double curvature, float* upper_plane, float* lower_plane)
      : g_(g), window_(window), near_steps_(near_steps), far_lines_(far_lines), early_exit_(early_exit) {
    walks_[0] = {1.0, curvature, upper_plane};
    walks_[1] = {-1.0, -curvature, lower_plane};
    n_walks_ = lower_plane ? 2 : 1;
    near_ = near_crossings(g, near_steps, kInf, curvature);
    steps_ = step_lines(g);
    g.window_span(window, wa_, wb_, lo_, hi_);
    last_step_ = wa_ < wb_ ? std::max(g.step_at(wa_), g.step_at(wb_ - 1)) : -1;
    // Hull points are at least far_gap ahead of any cell that queries them (the nearest is the
    // minor crossing between near_steps and near_steps + 1 steps ahead); where a sheared frame
    // makes that bound useless (far_gap <= 0), no far-field search is skipped.
    same_ = 1e-9 * g.t_step;
    per_cell_ = std::abs(g.k) == 0.5 ? 2 : 1;
    on_lines_ = g.k == 0.0 || std::abs(g.k) == 1.0 || per_cell_ == 2;
    far_gap_ = std::max(0.0, near_steps * g.t_step - std::abs(g.t_minor));
    inv_far_gap_ = far_gap_ > 0.0 ? 1.0 / far_gap_ : kInf;
  }

  int walks() const { return n_walks_; }
  // Lines per band (it keeps one hull more), and the samples a line can hold. Half-slope lines
  // take one sample a step, so a band keeps twice the lines in the same arena: a row's strip
  // stays kBand cells wide.
  int band_lines() const { return kBand * per_cell_; }
  std::size_t line_capacity() const { return (2 * static_cast<std::size_t>(g_.major_n) + 2) / per_cell_; }

  // Lines holding the window's cells: the first band's first line and the number of bands.
  long first_line() const { return static_cast<long>(std::floor(per_cell_ * (lo_ - max_shift()))) - 1; }
  long bands() const {
    if (wa_ >= wb_ || lo_ >= hi_) return 0;
    const long last = static_cast<long>(std::floor(per_cell_ * (hi_ - 1 - min_shift()))) + 1;
    return (last - first_line()) / band_lines() + 1;
  }

  // The band of strips from line m0, with each walk's hulls (band_lines() + 1, line_capacity() samples
  // per step each) and row-sized scratch of slopes.
  void run_band(long m0, const WalkState* state) const {
    const SweepGeometry& g = g_;
    for (int w = 0; w < n_walks_; ++w) {
      for (int l = 0; l <= band_lines(); ++l) state[w].hulls[l].clear();
    }
    if (on_lines_) {
      for (int step = 0; step <= last_step_; ++step) cells_on_lines(m0, steps_[static_cast<std::size_t>(step)], state);
      return;
    }
    BandSamples samples;
    for (int step = 0; step <= last_step_; ++step) {
      // Samples from more than near_steps steps back join their line's hull, far to near: the
      // row crossing, then the minor grid line crossed just after it.
      if (step > near_steps_) add_samples(m0, step - near_steps_ - 1, state, samples);
      const StepLines& here = steps_[static_cast<std::size_t>(step)];
      const int major = here.major;
      if (major < wa_ || major >= wb_) continue;
      const int a = static_cast<int>(std::max<long>(lo_, here.first_cell(m0)));
      const int b = static_cast<int>(std::min<long>(hi_, here.first_cell(m0 + kBand)));
      if (a >= b) continue;
      near_field(g, near_, major, a, b, state[0].best, n_walks_ > 1 ? state[1].best : nullptr);
      for (int w = 0; w < n_walks_; ++w) {
        far_field(walks_[w], m0, here, a, b, state[w]);
        write_angles(g, window_, major, a, b, state[w].best, walks_[w].sign, walks_[w].plane);
      }
    }
  }

 private:
  double min_shift() const { return std::min(wa_ * g_.k, (wb_ - 1) * g_.k); }
  double max_shift() const { return std::max(wa_ * g_.k, (wb_ - 1) * g_.k); }

  // This step's samples of the band's lines join their hulls, far to near on each line: the row
  // crossing, then the minor grid line crossed just after it. Every line sits at the same fraction
  // of a cell, so the heights come from vector loops over the lines (once for all walks); only the
  // pushes go line by line.
  void add_samples(long m0, int step, const WalkState* state, BandSamples& out) const {
    const SweepGeometry& g = g_;
    const StepLines& s = steps_[static_cast<std::size_t>(step)];
    auto clamp_line = [](long l) { return static_cast<int>(std::clamp<long>(l, 0, kBand + 1)); };
    // Row crossings, linear along the minor axis: line m0 + l lies at cell i0 + l plus fx.
    const double base = std::floor(s.shift), fx = s.shift - base;
    const long i0 = m0 + static_cast<long>(base);
    const int ra = clamp_line(-i0), rb = clamp_line(g.minor_n - (fx > 0.0 ? 1 : 0) - i0);
    const float* zr = g.row(s.major);  // indexed from the row's start: i0 may be negative
    const double t0 = s.major * g_.t_major + (static_cast<double>(i0) + fx) * g_.t_minor;
    if (fx > 0.0) {
      for (int l = ra; l < rb; ++l) out.row_z[l] = zr[i0 + l] + fx * (static_cast<double>(zr[i0 + l + 1]) - zr[i0 + l]);
    } else {
      for (int l = ra; l < rb; ++l) out.row_z[l] = zr[i0 + l];
    }
    for (int l = ra; l < rb; ++l) out.row_t[l] = t0 + l * g_.t_minor;
    // Crossings of a minor grid line, linear across the two rows: line m0 + l at cell x0 + l.
    const StepLines* next = step + 1 < g.major_n ? &steps_[static_cast<std::size_t>(step) + 1] : nullptr;
    int ca = 0, cb = 0;
    if (next && next->crossing) {
      const long x0 = m0 + next->cross_at;
      ca = clamp_line(-x0), cb = clamp_line(g.minor_n - x0);
      const float* z0 = g.row(next->major);
      const float* z1 = g.row(next->major + g.toward);
      const double lambda = next->lambda;
      const double tc = (next->major + g.toward * lambda) * g_.t_major + static_cast<double>(x0) * g_.t_minor;
      for (int l = ca; l < cb; ++l)
        out.cross_z[l] = z0[x0 + l] + lambda * (static_cast<double>(z1[x0 + l]) - z0[x0 + l]);
      for (int l = ca; l < cb; ++l) out.cross_t[l] = tc + l * g_.t_minor;
    }
    for (int w = 0; w < n_walks_; ++w) {
      const Walk& walk = walks_[w];
      for (int l = ra; l < rb; ++l) out.row_f[l] = walk.folded(out.row_t[l], out.row_z[l]);
      for (int l = ca; l < cb; ++l) out.cross_f[l] = walk.folded(out.cross_t[l], out.cross_z[l]);
      // NaN heights (nodata) never occlude.
      LineHull* hulls = state[w].hulls;
      // All row crossings, then all minor crossings: each line still gets its samples far to near,
      // and a line's second push no longer waits on its first (about 5% faster on BM_Sweep15).
      for (int l = ra; l < rb; ++l) {
        if (!std::isnan(out.row_f[l])) hulls[l].push({out.row_t[l], out.row_f[l]}, same_);
      }
      for (int l = ca; l < cb; ++l) {
        if (!std::isnan(out.cross_f[l])) hulls[l].push({out.cross_t[l], out.cross_f[l]}, same_);
      }
    }
  }

  // Along an axis or a diagonal every line runs through cell centres and holds no other sample
  // (no minor grid line is crossed between steps), so a cell's own ray is its line: the cell is the
  // line's next sample, and pushing it finds its exact horizon (the design, Stewart's),
  // with no near field and no search. Along a half slope (k = ±1/2) lines run half a cell apart:
  // at each step every other line passes through a cell centre and the rest through the midpoints
  // between two cells of the row, which they read linearly (the mesh is linear along rows); they
  // cross no other grid line between steps, so the same holds at twice the pushes. Every cell of
  // the band is pushed, those outside the window too (they occlude).
  void cells_on_lines(long m0, const StepLines& here, const WalkState* state) const {
    const int major = here.major;
    const long per = per_cell_;
    const long s = std::lround(per * here.shift);  // cell i lies on line per * i - s
    // The first cell (or midpoint after it) whose line is at or after line m.
    auto first_at = [&](long m, long midpoint) {
      const long x = m + s - midpoint;
      return x >= 0 ? (x + per - 1) / per : -((-x) / per);
    };
    const int a = static_cast<int>(std::max<long>(0, first_at(m0, 0)));
    const int b = static_cast<int>(std::min<long>(g_.minor_n, first_at(m0 + band_lines(), 0)));
    const int ma = per == 2 ? static_cast<int>(std::max<long>(0, first_at(m0, 1))) : 0;
    const int mb = per == 2 ? static_cast<int>(std::min<long>(g_.minor_n - 1, first_at(m0 + band_lines(), 1))) : 0;
    if (a >= b && ma >= mb) return;
    const float* zrow = g_.row(major);
    const double t_row = major * g_.t_major;
    for (int w = 0; w < n_walks_; ++w) {
      const Walk& walk = walks_[w];
      LineHull* hulls = state[w].hulls;  // line m's hull at hulls[m - m0]
      const long base = -m0 - s;
      for (int i = ma; i < mb; ++i) {
        const double z = zrow[i] + 0.5 * (static_cast<double>(zrow[i + 1]) - zrow[i]);
        if (std::isnan(z)) continue;  // nodata never occludes
        const double t = t_row + (i + 0.5) * g_.t_minor;
        hulls[base + 2 * i + 1].push<false>({t, walk.folded(t, z)}, same_);
      }
      float* best = state[w].best;
      for (int minor = a; minor < b; ++minor) {
        const float zc = zrow[minor];
        if (std::isnan(zc)) continue;  // written as NaN; nodata never occludes
        const double t = t_row + minor * g_.t_minor;
        const HullPoint p{t, walk.folded(t, zc)};
        const HullPoint* tangent = hulls[base + per * minor].push<false>(p, same_);
        best[minor] = tangent ? static_cast<float>((tangent->z - p.z) / (tangent->t - p.t) + 2.0 * walk.c * t)
                              : -std::numeric_limits<float>::infinity();
      }
      const int wa = std::max(a, lo_), wb = std::min(b, hi_);
      if (major >= wa_ && major < wb_ && wa < wb) write_angles(g_, window_, major, wa, wb, best, walk.sign, walk.plane);
    }
  }

  // The lines of its strip a row's cells ask: both; the first (no offset); or the nearer, `line`, or
  // the other where `line` has no hull yet (near the raster's sides).
  enum class Ask { both, first, nearer };

  // Beyond the near field each cell, at its own height, takes its tangent to the hulls of the lines
  // beside it (both, or the nearer: far_lines), unless the hulls' envelopes (their highest points,
  // then LineHull::under_slope) show that they cannot beat its near field. Which lines a cell asks
  // depends only on the row's offset, so the row picks the loop: both lines, their slopes (not
  // angles) interpolated by the offset, one arctangent per cell; or one line. With no offset (along
  // axes and diagonals) a cell lies on its first line and only that one counts.
  void far_field(const Walk& walk, long m0, const StepLines& here, int a, int b, const WalkState& state) const {
    const double fu = here.offset;
    if (fu == 0.0)
      far_cells<Ask::first>(walk, m0, here, a, b, state, 0);
    else if (far_lines_ == 2)
      far_cells<Ask::both>(walk, m0, here, a, b, state, 0);
    else
      far_cells<Ask::nearer>(walk, m0, here, a, b, state, fu > 0.5 ? 1 : 0);
  }

  // The far field of one row's cells [a, b), each asking the lines of its strip that kAsk names.
  template <Ask kAsk>
  void far_cells(const Walk& walk, long m0, const StepLines& here, int a, int b, const WalkState& state,
                 int line) const {
    constexpr int kAsked = kAsk == Ask::both ? 2 : 1;
    const float* zrow = g_.row(here.major);
    LineHull* hulls = state.hulls;
    float* best = state.best;
    const double c = walk.c;
    const double weight_of[2] = {1.0 - here.offset, here.offset};
    // The bounds need every hull point ahead of the cell (far_gap_ > 0).
    const bool skips = early_exit_ && far_gap_ > 0.0;
    for (int minor = a; minor < b; ++minor) {
      const float zc = zrow[minor];
      if (std::isnan(zc)) continue;
      const double t = here.major * g_.t_major + minor * g_.t_minor;
      const long m = minor + here.cell_line;
      const HullPoint p{t, walk.folded(t, zc)};
      LineHull* pair = hulls + (m - m0);  // the strip's two lines
      int used[kAsked];
      if constexpr (kAsk == Ask::both) {
        used[0] = 0, used[1] = 1;
      } else if constexpr (kAsk == Ask::first) {
        used[0] = 0;
      } else {
        used[0] = pair[line].n == 0 && pair[1 - line].n > 0 ? 1 - line : line;
      }
      const double near = best[minor];
      const double near_folded = near - 2.0 * c * t;  // in the hulls' folded heights
      if (skips) {
        // First the cheapest bound, the highest point over the smallest gap (under_slope implies
        // it, but this one reads only the hulls' tops).
        double top = pair[used[0]].top;
        if constexpr (kAsked == 2) top = std::max(top, pair[1].top);
        const double rise = top - p.z;
        bool hidden = near_folded >= (rise > 0.0 ? rise * inv_far_gap_ : 0.0);
        if (!hidden) {
          hidden = true;
          for (const int l : used) hidden = hidden && pair[l].under_slope(p, near_folded);
        }
        if (hidden) continue;
      }
      // Slopes are interpolated in folded heights: the weights sum to one wherever the lines have
      // hulls, and adding 2ct back commutes with the weighted mean.
      double far = 0.0, weight = 0.0;
      for (const int l : used) {
        LineHull& h = pair[l];
        if (h.n == 0) continue;
        const double w = kAsk == Ask::both ? weight_of[l] : 1.0;
        far += w * h.tangent_slope(p, l), weight += w;
      }
      if (weight > 0.0) best[minor] = static_cast<float>(std::max(near, far / weight + 2.0 * c * t));
    }
  }

  const SweepGeometry& g_;
  const Window& window_;
  int near_steps_;
  int far_lines_;    // lines whose hulls a cell asks: 2 (interpolated) or 1 (the nearer)
  bool early_exit_;  // skip searches that cannot change the horizon (off: for tests)
  Walk walks_[kMaxWalks];
  int n_walks_ = 1;
  double far_gap_ = 0, inv_far_gap_ = kInf;
  double same_ = 0;        // samples closer than this along a line are one (see LineHull::push)
  bool on_lines_ = false;  // every cell lies on a line (cells_on_lines)
  int per_cell_ = 1;       // lines per cell across the minor axis: 2 on half slopes, where k = ±1/2
  std::vector<NearCrossing> near_;
  std::vector<StepLines> steps_;
  int wa_ = 0, wb_ = 0, lo_ = 0, hi_ = 0, last_step_ = -1;
};

// What a band's walk writes: its hulls and their arena (33 MB per walk at 4000 x 4000), and a
// row-sized scratch of slopes per walk. Each worker keeps one from band to band and direction to
// direction rather than faulting in a fresh arena for every direction (worth 2-3% of user time on
// BM_Sweep15, within the machine's noise).
class BandScratch {
 public:
  // Hulls for `walks` walks over `band_lines` + 1 lines of at most `capacity` samples each and
  // slopes for rows of `row` cells, into `state`.
  void prepare(int band_lines, std::size_t capacity, int walks, std::size_t row, WalkState* state) {
    const std::size_t per_walk = static_cast<std::size_t>(band_lines) + 1, lines = per_walk * walks;
    if (capacity * lines > points_size_) {
      points_ = allocate_large<HullPoint>(capacity * lines);
      points_size_ = capacity * lines;
    }
    hulls_.resize(lines);
    for (std::size_t l = 0; l < lines; ++l) hulls_[l].points = points_.get() + capacity * l;
    best_.resize(row * walks);
    for (int w = 0; w < walks; ++w) state[w] = {hulls_.data() + per_walk * w, best_.data() + row * w};
  }

 private:
  LargeBuffer<HullPoint> points_;
  std::size_t points_size_ = 0;
  std::vector<LineHull> hulls_;
  std::vector<float> best_;
};
using BandScratches = tbb::enumerable_thread_specific<BandScratch>;

// One direction over the whole buffer; writes the horizon angles of the window's cells into
// `upper_plane` and, unless it is null, their lowest angles into `lower_plane` (both window-sized
// and row-major, NaN on nodata cells).
//
// Parallel lines one cell apart cover the raster, sampled where they cross grid lines (each major
// step, read linearly between neighbouring cell centres, and each minor grid line between steps,
// read along it): the shared mesh peaks only there. A cell's own ray runs between two lines at a
// constant offset. Its first near_steps steps are read exactly, as the march does: near terrain
// moves the angle most, and there a line's sideways offset would look like a slope. Beyond them
// the cell takes its tangent to the nearer line's hull, or to both (far_lines); line samples join
// their hull only once they are more than near_steps behind the current step. The near field runs
// in vector blocks, so 64 steps cost only about 10% more than 16 at 4000 x 4000 (the far field's
// skipped searches gain on them); with one line they bring the city sample's p99 (64 directions)
// from 0.0073 to 0.0028.
// With a radius there are no hulls: every crossing within it is near.
void sweep_direction(const Terrain& terrain, const float* transposed, const Window& window, double azimuth,
                     double curvature, int near_steps, int far_lines, bool early_exit, double radius,
                     BandScratches& scratches, float* upper_plane, float* lower_plane) {
  const SweepGeometry g = make_geometry(terrain, transposed, azimuth);
  const std::size_t row = static_cast<std::size_t>(g.minor_n);
  if (std::isfinite(radius)) {
    std::vector<float> best(row * DirectionSweep::kMaxWalks);
    float* lowest = lower_plane ? best.data() + row : nullptr;
    const int steps = static_cast<int>(std::min<double>(g.major_n, std::floor(radius / g.t_step) + 1));
    const auto near = near_crossings(g, steps, radius, curvature);
    int wa, wb, lo, hi;
    g.window_span(window, wa, wb, lo, hi);
    for (int major = wa; major < wb && lo < hi; ++major) {
      near_field(g, near, major, lo, hi, best.data(), lowest);
      write_angles(g, window, major, lo, hi, best.data(), 1.0, upper_plane);
      if (lowest) write_angles(g, window, major, lo, hi, lowest, -1.0, lower_plane);
    }
    return;
  }
  const DirectionSweep sweep(g, window, near_steps, far_lines, early_exit, curvature, upper_plane, lower_plane);
  const long first = sweep.first_line(), bands = sweep.bands();
  // Bands are independent and write disjoint cells, so they run in parallel too: the last
  // directions of a run no longer leave a core idle. Isolated, so that a worker waiting for this
  // direction's bands takes no other direction (which might wait for this one to be handed over).
  tbb::this_task_arena::isolate([&] {
    tbb::parallel_for(0L, bands, [&](long band) {
      WalkState state[DirectionSweep::kMaxWalks];
      scratches.local().prepare(sweep.band_lines(), sweep.line_capacity(), sweep.walks(), row, state);
      sweep.run_band(first + band * sweep.band_lines(), state);
    });
  });
}

class SweepEngine final : public HorizonEngine {
 public:
  explicit SweepEngine(const HorizonParams& p) : p_(p) {
    if (p_.samples == 0) p_.samples = 64;
    if (p_.samples < 1 || p_.samples > 4096) throw Error("--samples (exact near steps) must be 1 to 4096 for sweep");
    if (p_.radius < 0.0 || !std::isfinite(p_.radius)) throw Error("--radius must be positive (or 0 for unlimited)");
    if (p_.far_lines != 1 && p_.far_lines != 2) throw Error("--far-lines must be 1 or 2 for sweep");
  }
  std::string_view name() const override { return "sweep"; }
  std::string_view citation() const override {
    return "upper convex hull sweep along digital lines (after Stewart 1998, IEEE TVCG 4(1)); unlimited radius, or "
           "every crossing within --radius";
  }
  std::map<std::string, std::string> describe() const override {
    return {{"METHOD", "sweep"},
            {"DIRECTIONS", std::to_string(p_.directions)},
            {"RADIUS_M", p_.radius > 0 ? number_text(p_.radius) : "unlimited"},
            {"NEAR_STEPS", p_.radius > 0     ? "all within the radius"
                           : on_grid_lines() ? "none (every direction on the grid's lines: exact)"
                                             : std::to_string(p_.samples)},
            {"FAR_LINES", p_.radius > 0     ? "none (no hulls within a radius)"
                          : on_grid_lines() ? "none (every direction on the grid's lines: exact)"
                                            : std::to_string(p_.far_lines)}};
  }
  bool on_grid_lines() const { return p_.spacing == AzimuthSpacing::grid_lines; }
  double curvature_coefficient(const Terrain& terrain) const override {
    const double reach = p_.radius > 0 ? p_.radius : ground_diagonal(terrain);  // unlimited: the whole raster
    return detail::curvature_coefficient(p_, reach, terrain.frame.earth_radius());
  }
  double radius() const override { return p_.radius > 0 ? p_.radius : std::numeric_limits<double>::infinity(); }
  const HorizonParams& params() const override { return p_; }
  // Direction k's share of progress over `cells`: the shares add up to all of them.
  std::uint64_t direction_share(std::uint64_t cells, int k) const {
    const std::uint64_t n = static_cast<std::uint64_t>(p_.directions);
    return cells * (k + 1) / n - cells * k / n;
  }
  void compute_window(const Terrain& terrain, const Window& window, HorizonField& out,
                      ProgressCounter& progress) const override {
    out.resize(window.cols, window.rows, p_.directions, p_.lower);
    const Inputs in = inputs(terrain, out);
    BandScratches scratches;
    tbb::parallel_for(0, p_.directions, [&](int k) {
      sweep(terrain, in, window, k, scratches, out.upper_plane(k), p_.lower ? out.lower_plane(k) : nullptr);
      progress.advance(direction_share(window.cells(), k));
    });
  }

  // Workers take directions in order; whichever finishes the next direction to hand over hands it
  // and any finished after it to `take`, one at a time (planes finished early wait). So only the
  // directions in progress, and those waiting for an earlier one, are held: a few planes, not all.
  // A slow `take` (compressing a GeoTIFF band) must not let the other workers race ahead: a worker
  // starts direction k only once k is within `ahead` of the next to hand over. The worker holding
  // that next direction never waits, so it always arrives; `take` runs isolated, so that a worker
  // inside it cannot pick up a new direction (which might wait for the very direction it hands).
  bool streams_directions() const override { return true; }
  void compute_window_directions(const Terrain& terrain, const Window& window, HorizonField& out,
                                 ProgressCounter& progress, const DirectionBatchSink& take) const override {
    out.resize(0, 0, p_.directions, false);
    out.cols = window.cols, out.rows = window.rows;
    const Inputs in = inputs(terrain, out);
    const std::size_t cells = window.cells();
    struct Planes {
      LargeBuffer<float> upper, lower;
    };
    std::mutex mutex;
    std::map<int, Planes> finished;
    std::vector<Planes> spare;
    int next = 0;  // the next direction to hand over
    std::condition_variable handed;
    const int ahead = 2 * tbb::this_task_arena::max_concurrency();
    bool handing = false;
    std::atomic<int> started{0};
    BandScratches scratches;
    tbb::parallel_for(0, p_.directions, [&](int) {
      const int k = started++;
      Planes planes;
      {
        std::unique_lock<std::mutex> lock(mutex);
        handed.wait(lock, [&] { return k < next + ahead; });
        if (!spare.empty()) planes = std::move(spare.back()), spare.pop_back();
      }
      if (!planes.upper) {
        planes.upper = allocate_large<float>(cells);
        if (p_.lower) planes.lower = allocate_large<float>(cells);
      }
      sweep(terrain, in, window, k, scratches, planes.upper.get(), planes.lower.get());
      progress.advance(direction_share(cells, k));
      std::unique_lock<std::mutex> lock(mutex);
      finished.emplace(k, std::move(planes));
      if (handing) return;  // the worker handing over will find it
      handing = true;
      while (!finished.empty() && finished.begin()->first == next) {
        Planes ready = std::move(finished.begin()->second);
        finished.erase(finished.begin());
        lock.unlock();
        tbb::this_task_arena::isolate([&] { take(next, 1, ready.upper.get(), ready.lower.get()); });
        lock.lock();
        spare.push_back(std::move(ready));
        ++next;
        handed.notify_all();
      }
      handing = false;
    });
  }

 private:
  // What every direction reads: the curvature coefficient and the heights transposed, so that lines
  // advancing by columns read contiguous memory too.
  struct Inputs {
    double c;
    std::vector<double> azimuth;  // of each direction (HorizonField::set_azimuth)
    LargeBuffer<float> transposed;
  };
  Inputs inputs(const Terrain& terrain, const HorizonField& field) const {
    Inputs in;
    in.c = curvature_coefficient(terrain);
    for (int k = 0; k < p_.directions; ++k) in.azimuth.push_back(field.set_azimuth(k));
    const int W = terrain.width(), H = terrain.height();
    in.transposed = allocate_large<float>(static_cast<std::size_t>(W) * H);
    // In tiles, so that both the reads and the writes stay within cache lines already loaded; bands
    // of columns in parallel (each writes its own rows of the copy), which no direction can start
    // without (about 0.1 s of one core at 4000 x 4000).
    constexpr int kTile = 64;
    tbb::parallel_for(0, (W + kTile - 1) / kTile, [&](int tile) {
      const int c0 = tile * kTile;
      for (int r0 = 0; r0 < H; r0 += kTile) {
        for (int col = c0; col < std::min(W, c0 + kTile); ++col) {
          for (int r = r0; r < std::min(H, r0 + kTile); ++r)
            in.transposed[static_cast<std::size_t>(col) * H + r] = terrain.heights(col, r);
        }
      }
    });
    return in;
  }
  void sweep(const Terrain& terrain, const Inputs& in, const Window& window, int k, BandScratches& scratches,
             float* upper, float* lower) const {
    sweep_direction(terrain, in.transposed.get(), window, in.azimuth[static_cast<std::size_t>(k)], in.c, p_.samples,
                    p_.far_lines, p_.early_exit, radius(), scratches, upper, lower);
  }

  HorizonParams p_;
};

}  // namespace

std::unique_ptr<HorizonEngine> make_sweep_engine(const HorizonParams& params) {
  return std::make_unique<SweepEngine>(params);
}

}  // namespace skyview::detail
