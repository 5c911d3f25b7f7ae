#pragma once
// Where a ray's ground track may run in a buffer: every engine's tracks end where they leave it.
// At the raster's edges that is the raster's extent, half a cell beyond the outer cell centres;
// elsewhere (a tile's or block's cut inside the raster, whose halo already covers the radius) the
// buffer's outer cell centres, as before. The one-cell ring that extend_at_raster_edges grows
// (copies of the boundary cells, or their slope continued) only carries heights between the outer
// centres and the extent, for rays nearly along the boundary (meridian convergence); it is not
// terrain beyond it. Until Dec 7 tracks ran on over the ring to its centres, and a building touching
// the edge cast its copy's shadow: 74.2 degrees where the raster shows nothing
// (Shadow.TheRingBeyondTheRasterEdgeCastsNoShadow).
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "skyview/raster/terrain.h"

namespace skyview::detail {

// A box of pixel positions in a buffer, bounds included.
struct TrackBox {
  double col_lo = 0, row_lo = 0, col_hi = 0, row_hi = 0;

  bool contains(double col, double row) const {
    return col >= col_lo && col <= col_hi && row >= row_lo && row <= row_hi;
  }

  // Ground distance from (col, row), inside the box, to where the track with pixel steps (pc, pr)
  // per metre leaves it; infinity for a track that stays (no step at all).
  double exit(double col, double row, double pc, double pr) const {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    const double to_c = pc > 0 ? (col_hi - col) / pc : (pc < 0 ? (col_lo - col) / pc : kInf);
    const double to_r = pr > 0 ? (row_hi - row) / pr : (pr < 0 ? (row_lo - row) / pr : kInf);
    return std::min(to_c, to_r);
  }
};

// The raster's extent in the buffer's pixel positions, within its cell centres.
inline TrackBox track_box(const Terrain& t) {
  const double extent_c0 = -0.5 - t.origin_col, extent_c1 = t.raster_width() - 0.5 - t.origin_col;
  const double extent_r0 = -0.5 - t.origin_row, extent_r1 = t.raster_height() - 0.5 - t.origin_row;
  return {std::max(0.0, extent_c0), std::max(0.0, extent_r0), std::min<double>(t.width() - 1, extent_c1),
          std::min<double>(t.height() - 1, extent_r1)};
}

// The ground distance of the last row or column crossing at or before `end` metres along the
// track from (col, row) with pixel steps (pc, pr) per metre; 0 where there is none. The mesh
// every method reads peaks along a track only on grid lines, and the march and the sweep read it
// only there: a ray cast that stops at `end` itself would count the ramp beyond the last crossing.
inline double last_crossing_within(double col, double row, double pc, double pr, double end) {
  if (std::isinf(end)) return end;
  double d = 0.0;
  for (const auto& [at, per_metre] : {std::pair{col, pc}, std::pair{row, pr}}) {
    if (per_metre == 0.0) continue;
    const double step = std::abs(per_metre);
    // How far past its last grid line the start is, looking along the track.
    const double phase = per_metre > 0 ? at - std::floor(at) : std::ceil(at) - at;
    const double lines = std::floor((phase + end * step) * (1.0 + 1e-12));
    if (lines >= 1.0) d = std::max(d, (lines - phase) / step);
  }
  return std::min(d, end);
}

}  // namespace skyview::detail
