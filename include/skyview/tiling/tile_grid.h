#pragma once
// A raster cut into square tiles of `tile_size` cells (the last row and column of tiles hold the
// remainder), each computed on its window grown by a halo: with a halo at least as wide as the search
// radius, a tile's horizons are those of the whole raster (Terrain's origin and full size place it).
#include <cstdint>
#include <string>

#include "skyview/raster/terrain.h"

namespace skyview {

class TileGrid {
 public:
  // Throws skyview::UsageError for a tile size below 1; a raster of at least 1 x 1 cells.
  TileGrid(int width, int height, int tile_size);

  int width() const { return width_; }
  int height() const { return height_; }
  int tile_size() const { return size_; }
  int tile_cols() const { return cols_; }
  int tile_rows() const { return rows_; }
  int count() const { return cols_ * rows_; }
  // Tile `index` (row-major from the top-left) in the raster's cells; its row and column of tiles.
  Window core(int index) const;
  int tile_row(int index) const { return index / cols_; }
  int tile_col(int index) const { return index % cols_; }

 private:
  int width_, height_, size_, cols_, rows_;
};

// `core` grown by `halo` cells on every side, clipped to the raster of `width` x `height` cells:
// the window a tile reads.
Window with_halo(const Window& core, int halo, int width, int height);

// Where `core` lies inside `read` (a window of the same raster that holds it).
Window inside(const Window& core, const Window& read);

}  // namespace skyview
