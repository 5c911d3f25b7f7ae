#pragma once
// One direction of the sweep over a whole buffer (sweep.cpp has the method).
#include <tbb/enumerable_thread_specific.h>

#include <cstddef>
#include <vector>

#include "horizon/sweep_hull.h"
#include "skyview/core/large_pages.h"
#include "skyview/raster/terrain.h"

namespace skyview::detail::sweep {

// A walk's state in the band being walked.
struct WalkState {
  LineHull* hulls = nullptr;  // band_lines() + 1, in their own arena
  float* best = nullptr;      // row-sized scratch of slopes
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
                     BandScratches& scratches, float* upper_plane, float* lower_plane);

}  // namespace skyview::detail::sweep
