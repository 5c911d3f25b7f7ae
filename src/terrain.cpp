#include "skyview/terrain.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace skyview {

double ground_diagonal(const Terrain& t) {
  const Jacobian j = t.frame.at(t.origin_col, t.origin_row);
  return std::hypot(t.width() * std::hypot(j.a, j.c), t.height() * std::hypot(j.b, j.d));
}

int halo_cells(const Terrain& t, double radius) {
  if (!std::isfinite(radius)) return std::max(t.full_width, t.full_height);
  // The smallest ground size of a pixel step anywhere bounds how many cells `radius` spans.
  double smallest = std::numeric_limits<double>::infinity();
  for (int r : {0, t.height() / 2, t.height() - 1}) {
    for (int c : {0, t.width() / 2, t.width() - 1}) {
      smallest = std::min(smallest, t.frame.at(c + t.origin_col, r + t.origin_row).min_cell_size());
    }
  }
  return static_cast<int>(std::ceil(radius / (0.99 * smallest))) + 2;
}

Terrain crop_terrain(const Terrain& t, const Window& w, int halo, Window& inner) {
  const int c0 = std::max(0, w.col0 - halo), r0 = std::max(0, w.row0 - halo);
  const int c1 = std::min(t.width(), w.col0 + w.cols + halo), r1 = std::min(t.height(), w.row0 + w.rows + halo);
  Terrain out;
  out.heights = Grid<float>(c1 - c0, r1 - r0);
  for (int r = r0; r < r1; ++r) {
    std::copy_n(&t.heights(c0, r), c1 - c0, &out.heights(0, r - r0));
  }
  out.base_height = t.base_height;
  out.frame = t.frame;
  out.georef = t.georef.window(c0, r0);
  out.origin_col = t.origin_col + c0;
  out.origin_row = t.origin_row + r0;
  out.full_width = t.full_width;
  out.full_height = t.full_height;
  inner = {w.col0 - c0, w.row0 - r0, w.cols, w.rows};
  return out;
}

Terrain extend_at_raster_edges(const Terrain& t, const Window& w, Window& inner) {
  const int full_w = t.full_width > 0 ? t.full_width : t.width();
  const int full_h = t.full_height > 0 ? t.full_height : t.height();
  const int left = t.origin_col == 0 ? 1 : 0, top = t.origin_row == 0 ? 1 : 0;
  const int right = t.origin_col + t.width() == full_w ? 1 : 0, bottom = t.origin_row + t.height() == full_h ? 1 : 0;
  const int W = t.width(), H = t.height();
  Terrain out;
  out.heights = Grid<float>(W + left + right, H + top + bottom);
  for (int r = 0; r < out.height(); ++r) {
    const int src_r = std::clamp(r - top, 0, H - 1);
    float* row = &out.heights(0, r);
    std::copy_n(&t.heights(0, src_r), W, row + left);
    if (left) row[0] = row[1];
    if (right) row[W + left] = row[W + left - 1];
  }
  out.base_height = t.base_height;
  out.frame = t.frame;
  out.georef = t.georef.window(-left, -top);
  out.origin_col = t.origin_col - left;
  out.origin_row = t.origin_row - top;
  out.full_width = full_w;
  out.full_height = full_h;
  inner = {w.col0 + left, w.row0 + top, w.cols, w.rows};
  return out;
}

}  // namespace skyview
