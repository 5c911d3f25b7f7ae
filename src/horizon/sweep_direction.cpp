// The sweep's walk of one direction (sweep.cpp has the method): its lines' hulls band by band,
// the near field and the far field's tangents for every cell.
//
// Memory layout, the cost that matters: lines are walked in bands of kBand neighbouring lines
// from the far end to the near end. A band's hulls share one arena and its cells and line samples
// lie in a strip kBand + 1 cells wide (near-field reads reach near_steps |k| cells beyond), so the
// whole walk stays in the caches. Walking every line of the raster one row at a time instead
// loaded each line's hull from memory at every row (a cache miss per cell and direction: 2.8x
// slower at 4000 x 4000).
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "horizon/sweep_direction.h"
#include "horizon/sweep_geometry.h"
#include "horizon/sweep_hull.h"
#include "horizon/sweep_near_field.h"

namespace skyview::detail::sweep {

namespace {

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
    // Only samples inside the raster's extent (SweepGeometry::major_lo): tracks end there.
    int ra = clamp_line(std::max<long>(-i0, g.minor_first(static_cast<double>(i0) + fx)));
    int rb =
        clamp_line(std::min<long>(g.minor_n - (fx > 0.0 ? 1 : 0) - i0, g.minor_last(static_cast<double>(i0) + fx)));
    if (!g.major_inside(s.major)) rb = ra;
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
      ca = clamp_line(std::max<long>(-x0, g.minor_first(static_cast<double>(x0))));
      cb = clamp_line(std::min<long>(g.minor_n - x0, g.minor_last(static_cast<double>(x0))));
      if (!g.major_inside(next->major + g.toward * next->lambda)) cb = ca;
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
    // Only cells and midpoints inside the raster's extent (SweepGeometry::major_lo): tracks end there.
    if (!g_.major_inside(major)) return;
    const int a = static_cast<int>(std::max<long>(g_.minor_first(0.0), first_at(m0, 0)));
    const int b = static_cast<int>(std::min<long>(g_.minor_last(0.0), first_at(m0 + band_lines(), 0)));
    const int ma = per == 2 ? static_cast<int>(std::max<long>(g_.minor_first(0.5), first_at(m0, 1))) : 0;
    const int mb = per == 2 ? static_cast<int>(std::min<long>(std::min(g_.minor_n - 1, g_.minor_last(0.5)),
                                                              first_at(m0 + band_lines(), 1)))
                            : 0;
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

}  // namespace

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

}  // namespace skyview::detail::sweep
