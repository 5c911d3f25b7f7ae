#pragma once
// The mechanism the sampled and march methods share: from every cell, walk straight out
// along each azimuth and keep the steepest (and, on request, the shallowest) slope to the
// terrain. The methods differ only in where along the ray they look (a Placement policy).
//
// Early termination, from a max-height pyramid of the buffer:
// - top level: once the ray is at distance d, no farther terrain can rise above
//   (z_max - z0 - c d^2) / d, so the walk stops as soon as that bound cannot beat the slope
//   already found;
// - lower levels (blocks of 32 and 8 cells, each with a one-cell border so that interpolated
//   samples inside a block read only cells it covers): when the steepest slope found already
//   clears a block's highest cell over the whole stretch of ray inside the block, the walk jumps
//   to where the ray leaves it (the maximum-mipmap skip of heightfield ray tracers).
// With the lowest angle requested, a block is skipped only when its lowest cell cannot go
// below the shallowest slope found either. Both levels only skip samples that cannot change the
// result, so results are bit-identical with and without them (tested).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "earth_curvature.h"
#include "height_sampler.h"
#include "skyview/horizon/horizon_engine.h"
#include "skyview/horizon/point_horizons.h"
#include "track_box.h"

namespace skyview::detail {

inline std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// A uniform number in [0, 1) that depends only on the cell's place in the full raster and the
// seed, so tiles of a raster get the same rotations as a single run.
inline double cell_random(std::uint64_t global_id, std::uint64_t seed) {
  return static_cast<double>(splitmix64(global_id ^ splitmix64(seed)) >> 11) * 0x1.0p-53;
}

struct ScanSettings {
  int directions = 16;
  bool lower = false;
  bool early_exit = true;
  bool rotate = false;  // per-cell random rotation of the direction set, on top of the field's
  std::uint64_t seed = 0;
  double curvature = 0.0;  // c in drop = c d^2
  double max_distance = std::numeric_limits<double>::infinity();
};

// Settings shared by the ray methods, from their parameters (radius already defaulted).
ScanSettings scan_settings(const HorizonParams& p, const Terrain& terrain);

// Block extremes of the heights at one pyramid level: block (bx, by) covers cells
// [bx B, bx B + B] x [by B, by B + B], borders included.
struct MaxBlocks {
  int size = 0, shift = 0, cols = 0;  // size = 1 << shift
  std::vector<float> max, min;        // NaN-free; -inf / +inf for blocks of nodata only

  MaxBlocks(const Terrain& t, int log2_block)
      : size(1 << log2_block), shift(log2_block), cols((t.width() + size - 1) / size) {
    const int block = size;
    const int rows = (t.height() + block - 1) / block;
    max.assign(static_cast<std::size_t>(cols) * rows, -std::numeric_limits<float>::infinity());
    min.assign(max.size(), std::numeric_limits<float>::infinity());
    for (int r = 0; r < t.height(); ++r) {
      for (int c = 0; c < t.width(); ++c) {
        const float z = t.heights(c, r);
        if (std::isnan(z)) continue;
        // A cell on a block border belongs to the blocks on both sides of it.
        for (int by = std::max(0, (r - 1) / block); by <= r / block && by < rows; ++by) {
          if (r < by * block || r > by * block + block) continue;
          for (int bx = std::max(0, (c - 1) / block); bx <= c / block && bx < cols; ++bx) {
            if (c < bx * block || c > bx * block + block) continue;
            const std::size_t b = static_cast<std::size_t>(by) * cols + bx;
            max[b] = std::max(max[b], z);
            min[b] = std::min(min[b], z);
          }
        }
      }
    }
  }
};

// Placement must provide kDenseSteps (true when consecutive samples are about a cell apart) and
//   template <class Visit> void walk(double col, double row, double col_per_m, double row_per_m,
//                                    double max_distance, double curvature, Visit&& visit) const;
// calling visit(d, 1/d, curvature*d*d) for increasing distances d <= max_distance (where the track
// leaves the raster's extent, track_box.h) along the ray from pixel position (col, row) (a cell
// centre, or any point for point queries). visit returns a negative number to stop, or a distance
// r >= d: the walk goes on with its first sample farther than r.
//
// One cell's walk along every direction, with what all cells share (the direction set, the
// raster's extremes, the pyramid) built once.
template <class Placement>
class RayScanner {
 public:
  // `field`: whose sectors (HorizonField::sector_rotation and sectors) to scan.
  RayScanner(const Terrain& terrain, const ScanSettings& s, const Placement& placement, const HorizonField& field)
      : terrain_(terrain), s_(s), placement_(placement), sampler_(terrain), box_(track_box(terrain)) {
    for (float z : terrain.heights.values()) {
      if (!std::isnan(z)) {
        zmax_ = std::max<double>(zmax_, z);
        zmin_ = std::min<double>(zmin_, z);
      }
    }
    sin_k_.resize(s.directions);
    cos_k_.resize(s.directions);
    for (int k = 0; k < s.directions; ++k) {
      sin_k_[k] = std::sin(field.set_azimuth(k));
      cos_k_[k] = std::cos(field.set_azimuth(k));
    }
    // Only a placement that reads every crossing has runs of samples inside one block to skip.
    if (s.early_exit && Placement::kDenseSteps) {
      for (int shift : {5, 3}) {  // 32 and 8 cells
        const int b = 1 << shift;
        if (terrain.width() > 2 * b || terrain.height() > 2 * b) levels_.emplace_back(terrain, shift);
      }
    }
  }

  // The valid cell (col, row)'s horizons: direction k at up[plane * k] (and lo[plane * k] when
  // lowest angles are asked for); its rotation of the direction set at *rotation when rotating.
  void scan(int col, int row, float* up, float* lo, std::size_t plane, float* rotation) const {
    double rot = 0.0;
    if (s_.rotate) {
      rot = (cell_random(terrain_.global_id(col, row), s_.seed) - 0.5) * (2.0 * M_PI / s_.directions);
      *rotation = static_cast<float>(rot);
    }
    scan_from(col, row, terrain_.heights(col, row), rot, up, lo, plane, nullptr);
  }

  // The horizons seen from pixel position (x, y) inside the buffer at height z0 (the buffer's
  // units), the direction set turned by `rot`: what scan() does for a cell centre, for any point
  // (point queries: an observer above the surface between cell centres). With `rising`
  // (directions entries), each direction's steps of the steepest slope in order of distance, for
  // pictures that shade what a ray meets by its distance.
  void scan_from(double eye_col, double eye_row, double z0, double rot, float* up, float* lo, std::size_t plane,
                 std::vector<std::vector<RisingStep>>* rising) const {
    const Terrain& terrain = terrain_;
    const ScanSettings& s = s_;
    const HeightSampler& sampler = sampler_;
    const double c = s.curvature;
    const bool early = s.early_exit;
    constexpr double kInf = std::numeric_limits<double>::infinity();
    constexpr double kTieMargin = 1e-6;  // metres
    const TrackBox& box = box_;
    const double col = eye_col, row = eye_row;
    const double above = std::max(0.0, zmax_ - z0);  // an observer may stand above every cell
    const double below = std::min(0.0, zmin_ - z0);
    const double sr = std::sin(rot), cr = std::cos(rot);
    // Inverse Jacobian: metres east/north -> pixel columns/rows.
    const Jacobian j = terrain.frame.at(col + terrain.origin_col, row + terrain.origin_row);
    const double det = j.a * j.d - j.b * j.c;
    const double ie_c = j.d / det, in_c = -j.b / det, ie_r = -j.c / det, in_r = j.a / det;
    if (!s.lower) lo = nullptr;
    for (int k = 0; k < s.directions; ++k) {
      const double east = sin_k_[k] * cr + cos_k_[k] * sr;   // sin(az + rot)
      const double north = cos_k_[k] * cr - sin_k_[k] * sr;  // cos(az + rot)
      double pc = ie_c * east + in_c * north, pr = ie_r * east + in_r * north;
      // cos(90°) is 6e-17, not 0: keep rays along a row or column on it.
      if (std::abs(pc) < 1e-12 * std::abs(pr)) pc = 0.0;
      if (std::abs(pr) < 1e-12 * std::abs(pc)) pr = 0.0;
      double max_t = -std::numeric_limits<double>::infinity();
      double min_t = std::numeric_limits<double>::infinity();
      // Distance at which the track leaves the raster's extent (track_box.h), so samples need no
      // bounds check.
      const double exit = box.exit(col, row, pc, pr);
      const double inv_pc = pc != 0.0 ? 1.0 / pc : 0.0, inv_pr = pr != 0.0 ? 1.0 / pr : 0.0;
      std::size_t judged[2] = {SIZE_MAX, SIZE_MAX};  // the block of each level last judged
      std::vector<RisingStep>* steps = rising ? &(*rising)[static_cast<std::size_t>(k)] : nullptr;
      if (steps) steps->clear();
      placement_.walk(col, row, pc, pr, exit * (1.0 + 1e-12), c, [&](double d, double inv_d, double drop) {
        const double x = std::clamp(col + pc * d, box.col_lo, box.col_hi);
        const double y = std::clamp(row + pr * d, box.row_lo, box.row_hi);
        const double z = sampler.at(x, y);
        if (!std::isnan(z)) {
          const double t = (z - z0 - drop) * inv_d;
          if (steps && t > max_t) steps->push_back({static_cast<float>(d), static_cast<float>(t)});
          max_t = std::max(max_t, t);
          min_t = std::min(min_t, t);
        }
        if (early) {
          const double bound_hi = (above - drop) * inv_d;  // decreasing in d since above >= 0
          if (bound_hi <= max_t) {
            if (!lo) return -1.0;
            const double bound_lo = below * inv_d - c * s.max_distance;
            if (bound_lo >= min_t) return -1.0;
          }
        }
        // The largest block around this sample whose cells cannot beat max_t anywhere on
        // the ray's stretch through it (curvature only lowers them further). Each block is
        // judged once, when the ray enters it: checking every sample cost more than it saved.
        for (std::size_t l = 0; l < levels_.size(); ++l) {
          const MaxBlocks& level = levels_[l];
          const int bx = static_cast<int>(x) >> level.shift;  // x in the buffer: always a block
          const int by = static_cast<int>(y) >> level.shift;
          const std::size_t b = static_cast<std::size_t>(by) * level.cols + bx;
          if (b == judged[l]) continue;
          judged[l] = b;
          // The margin keeps a sample on the block's border, whose slope rounds differently
          // from this bound, from tying with max_t: skipped samples stay strictly below it.
          const double rise = level.max[b] - z0 + kTieMargin;
          if (rise > 0 && !(rise <= max_t * d)) continue;  // cheap test before the exit distance
          const double x0 = bx * level.size, y0 = by * level.size;
          const double leave_c = pc > 0 ? (x0 + level.size - col) * inv_pc : (pc < 0 ? (x0 - col) * inv_pc : kInf);
          const double leave_r = pr > 0 ? (y0 + level.size - row) * inv_pr : (pr < 0 ? (y0 - row) * inv_pr : kInf);
          const double leave = std::min(leave_c, leave_r);
          // rise / d' over [d, leave] peaks at d when rise > 0 and at leave otherwise.
          if (!(rise <= max_t * (rise > 0 ? d : leave))) continue;
          if (lo) {
            // (fall - c d'^2) / d' has no interior minimum on [d, leave]: check both ends.
            const double fall = level.min[b] - z0 - kTieMargin;
            if (!(std::min(fall / d - c * d, fall / leave - c * leave) >= min_t)) continue;
          }
          return std::max(d, leave);
        }
        return d;
      });
      up[plane * k] = std::isinf(max_t) ? 0.0f : static_cast<float>(std::atan(max_t));
      if (lo) lo[plane * k] = std::isinf(min_t) ? 0.0f : static_cast<float>(std::atan(min_t));
    }
  }

 private:
  const Terrain& terrain_;
  ScanSettings s_;
  Placement placement_;
  HeightSampler sampler_;
  TrackBox box_;
  double zmax_ = -std::numeric_limits<double>::infinity(), zmin_ = std::numeric_limits<double>::infinity();
  std::vector<double> sin_k_, cos_k_;
  std::vector<MaxBlocks> levels_;  // coarse first
};

// Every valid cell of `window`.
template <class Placement>
void scan_rays(const Terrain& terrain, const Window& window, HorizonField& out, ProgressCounter& progress,
               const ScanSettings& s, const Placement& placement) {
  out.resize(window.cols, window.rows, s.directions, s.lower);
  if (s.rotate) out.rotation.assign(static_cast<std::size_t>(window.cols) * window.rows, 0.0f);
  const RayScanner<Placement> scanner(terrain, s, placement, out);
  tbb::parallel_for(tbb::blocked_range<int>(0, window.rows), [&](const tbb::blocked_range<int>& range) {
    for (int wr = range.begin(); wr != range.end(); ++wr) {
      progress.stop_if_cancelled();
      const int row = window.row0 + wr;
      for (int wc = 0; wc < window.cols; ++wc) {
        const int col = window.col0 + wc;
        if (!terrain.valid(col, row)) continue;
        const std::size_t cell = out.cell(wc, wr);
        scanner.scan(col, row, out.upper.data() + cell, s.lower ? out.lower.data() + cell : nullptr, out.cells(),
                     s.rotate ? out.rotation.data() + cell : nullptr);
      }
      progress.advance(window.cols);
    }
  });
}

// The listed cells of the buffer, in `out` as a window of one row (cell i in column i); invalid
// cells keep NaN.
template <class Placement>
void scan_cells(const Terrain& terrain, const std::vector<CellIndex>& cells, HorizonField& out, const ScanSettings& s,
                const Placement& placement) {
  const int n = static_cast<int>(cells.size());
  out.resize(n, 1, s.directions, s.lower);
  if (s.rotate) out.rotation.assign(cells.size(), 0.0f);
  const RayScanner<Placement> scanner(terrain, s, placement, out);
  tbb::parallel_for(tbb::blocked_range<int>(0, n, 8), [&](const tbb::blocked_range<int>& range) {
    for (int i = range.begin(); i != range.end(); ++i) {
      if (!terrain.valid(cells[i].col, cells[i].row)) continue;
      scanner.scan(cells[i].col, cells[i].row, out.upper.data() + i, s.lower ? out.lower.data() + i : nullptr,
                   out.cells(), s.rotate ? out.rotation.data() + i : nullptr);
    }
  });
}

}  // namespace skyview::detail
