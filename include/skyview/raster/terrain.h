#pragma once
// The height field every horizon method reads: heights relative to a base elevation kept in
// double, so that millimetre relief on an 8848 m summit survives float storage; nodata as NaN.
// A Terrain may be a window (plus halo) of a larger raster: `origin_col/row` place it in the
// full raster and `full_width/height` give that raster's size, so results for a tile are
// the same as for the whole raster.
#include <cmath>
#include <cstdint>

#include "skyview/core/grid.h"
#include "skyview/raster/georeference.h"
#include "skyview/raster/ground_frame.h"

namespace skyview {

struct Terrain {
  Grid<float> heights;       // metres above `base_height`, NaN where nodata
  double base_height = 0.0;  // metres
  GroundFrame frame = GroundFrame::uniform(1.0);
  GeoReference georef;                  // of this buffer
  int origin_col = 0, origin_row = 0;   // where this buffer starts in the full raster
  int full_width = 0, full_height = 0;  // size of the full raster

  int width() const { return heights.width(); }
  int height() const { return heights.height(); }
  // The full raster's size (this buffer's where it is not known).
  int raster_width() const { return full_width > 0 ? full_width : width(); }
  int raster_height() const { return full_height > 0 ? full_height : height(); }
  bool valid(int col, int row) const { return !std::isnan(heights(col, row)); }
  double absolute_height(int col, int row) const { return base_height + heights(col, row); }
  // Global cell id, independent of tiling (seeds per-cell random rotations).
  std::uint64_t global_id(int col, int row) const {
    return static_cast<std::uint64_t>(row + origin_row) * 0x1000000ull + static_cast<std::uint64_t>(col + origin_col);
  }
};

// A rectangle of cells in a Terrain buffer's coordinates.
struct Window {
  int col0 = 0, row0 = 0, cols = 0, rows = 0;
  static Window whole(const Terrain& t) { return {0, 0, t.width(), t.height()}; }
  std::int64_t cells() const { return static_cast<std::int64_t>(cols) * rows; }
};

// One cell of a Terrain buffer.
struct CellIndex {
  int col = 0, row = 0;
};

// The buffer's diagonal on the ground in metres (by the Jacobian at its first cell): how far any
// ray within it can run.
double ground_diagonal(const Terrain& terrain);

// The ground frame at the full raster's centre (the buffer's where the full size is unknown): one
// Jacobian that every tile and block of a raster shares, for what must not differ between them
// (the sweep's lines, the direction set's rotation).
Jacobian raster_centre_jacobian(const Terrain& terrain);

// Cells of halo a window needs so that every sample within `radius` metres lies in the buffer.
int halo_cells(const Terrain& terrain, double radius);
// The same for the cells of `area` (in the raster's cells) of a raster with this ground frame.
int halo_cells(const GroundFrame& frame, const Window& area, double radius);

// A copy of `window` grown by `halo` cells (clipped to the buffer), placed in the full raster
// so that horizons computed on it equal those of the whole raster for the window's cells.
// `inner` receives the window's position inside the returned buffer.
Terrain crop_terrain(const Terrain& terrain, const Window& window, int halo, Window& inner);

// The buffer grown by one cell on each side where it ends at the full raster's edge, each new cell
// continuing its nearest boundary cell's slope outward (minmod-limited, at most 45°; nodata stays
// nodata); `inner` receives `window`'s position in it. The mesh over cell centres ends half a cell
// inside the raster's extent, so a ray nearly along the boundary from a boundary cell (due north
// from the outer column of a UTM raster, where grid north is a hair off true north) would leave it
// at once and miss terrain a few cells ahead in the same column; on the ring it runs on. The ring
// carries heights only up to the raster's extent, where every engine's track ends
// (src/horizon/track_box.h): it is not terrain beyond it.
Terrain extend_at_raster_edges(const Terrain& terrain, const Window& window, Window& inner);

}  // namespace skyview
