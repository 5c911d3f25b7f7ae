#include "skyview/tiling/tile_grid.h"

#include <algorithm>

#include "skyview/core/error.h"

namespace skyview {

TileGrid::TileGrid(int width, int height, int tile_size) : width_(width), height_(height), size_(tile_size) {
  if (tile_size < 1) throw UsageError("--tile-size must be at least 1 cell, not " + std::to_string(tile_size));
  if (width < 1 || height < 1)
    throw Error("a raster of " + std::to_string(width) + "x" + std::to_string(height) +
                " cells has no tiles (internal error)");
  cols_ = (width + tile_size - 1) / tile_size;
  rows_ = (height + tile_size - 1) / tile_size;
}

Window TileGrid::core(int index) const {
  const int c0 = tile_col(index) * size_, r0 = tile_row(index) * size_;
  return {c0, r0, std::min(size_, width_ - c0), std::min(size_, height_ - r0)};
}

Window with_halo(const Window& core, int halo, int width, int height) {
  const int c0 = std::max(0, core.col0 - halo), r0 = std::max(0, core.row0 - halo);
  const int c1 = std::min(width, core.col0 + core.cols + halo), r1 = std::min(height, core.row0 + core.rows + halo);
  return {c0, r0, c1 - c0, r1 - r0};
}

Window inside(const Window& core, const Window& read) {
  return {core.col0 - read.col0, core.row0 - read.row0, core.cols, core.rows};
}

}  // namespace skyview
