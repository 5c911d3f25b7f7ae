#pragma once
// The sweep's lines for one direction (sweep.cpp): parallel lines one cell apart, advancing along
// the major axis, and the crossings of each cell's own ray that the near field reads exactly.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "skyview/raster/terrain.h"

namespace skyview::detail::sweep {

constexpr double kInf = std::numeric_limits<double>::infinity();

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
  // Where samples may lie (track_box.h, in major and minor positions): tracks end where they leave
  // the raster's extent, and no sample beyond it joins a hull or a near field.
  double major_lo = 0, major_hi = 0, minor_lo = 0, minor_hi = 0;

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
  bool major_inside(double major) const { return major >= major_lo && major <= major_hi; }
  // The offsets i from `base` with base + i inside along the minor axis: [first, last).
  int minor_first(double base) const { return static_cast<int>(std::ceil(minor_lo - base)); }
  int minor_last(double base) const { return static_cast<int>(std::floor(minor_hi - base)) + 1; }
};

SweepGeometry make_geometry(const Terrain& terrain, const float* transposed, double azimuth);

// One crossing of every cell's own ray, at the same offset from each cell (so a row of cells
// reads it in one vector loop): the height p0[m] + w (p1[m] - p0[m]), where p0 and p1 are rows
// `ahead0` and `ahead1` steps ahead shifted by col0 and col1 along the minor axis. Either two
// neighbours along a row (a major-step crossing) or two rows at one minor index (the minor grid
// line crossed between two steps).
struct NearCrossing {
  int ahead0, col0, ahead1, col1;
  float w;
  float scale;           // 1 / distance
  float drop;            // curvature drop over the distance, in slope units
  double ahead, across;  // the sample's place: steps ahead and minor offset from the cell, exactly
};

// The first near_steps steps of a cell's own ray, and every minor grid line they cross, within
// `radius`; in order of distance.
std::vector<NearCrossing> near_crossings(const SweepGeometry& g, int near_steps, double radius, double c);

}  // namespace skyview::detail::sweep
