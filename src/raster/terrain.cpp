#include "skyview/raster/terrain.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace skyview {

double ground_diagonal(const Terrain& t) {
  const Jacobian j = t.frame.at(t.origin_col, t.origin_row);
  return std::hypot(t.width() * std::hypot(j.a, j.c), t.height() * std::hypot(j.b, j.d));
}

Jacobian raster_centre_jacobian(const Terrain& t) {
  if (t.full_width > 0 && t.full_height > 0) return t.frame.at(0.5 * t.full_width, 0.5 * t.full_height);
  return t.frame.at(t.origin_col + 0.5 * t.width(), t.origin_row + 0.5 * t.height());
}

int halo_cells(const Terrain& t, double radius) {
  if (!std::isfinite(radius)) return std::max(t.full_width, t.full_height);
  return halo_cells(t.frame, {t.origin_col, t.origin_row, t.width(), t.height()}, radius);
}

int halo_cells(const GroundFrame& frame, const Window& area, double radius) {
  if (!std::isfinite(radius)) return std::max(area.cols, area.rows);
  // The smallest ground size of a pixel step anywhere bounds how many cells `radius` spans.
  double smallest = std::numeric_limits<double>::infinity();
  for (int r : {0, area.rows / 2, area.rows - 1}) {
    for (int c : {0, area.cols / 2, area.cols - 1}) {
      smallest = std::min(smallest, frame.at(c + area.col0, r + area.row0).min_cell_size());
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
  const int full_w = t.raster_width(), full_h = t.raster_height();
  const int left = t.origin_col == 0 ? 1 : 0, top = t.origin_row == 0 ? 1 : 0;
  const int right = t.origin_col + t.width() == full_w ? 1 : 0, bottom = t.origin_row + t.height() == full_h ? 1 : 0;
  const int W = t.width(), H = t.height();
  // A ring cell continues its nearest boundary cell's slope outward, along each axis it lies
  // beyond: a copy of the boundary cell would stand above a slope falling off the raster and cast
  // a horizon on rays along the boundary. The slope is the gentler of the last two differences
  // into the boundary, or none where they disagree in sign or meet nodata (the minmod limiter of
  // finite-volume schemes), and at most 45°. So a plane goes on as a plane, corners included,
  // while a wall or spike at the edge is only copied, never raised; a boundary cell with nodata
  // one or two cells inward is copied too (one difference cannot tell a plane from a wall's foot). The
  // rule commutes with negating the terrain, as the lowest angles (its horizons) need.
  auto rise = [&](int col, int row, int dcol, int drow, double spacing) {
    const int c1 = col - dcol, r1 = row - drow, c2 = c1 - dcol, r2 = r1 - drow;
    if (c2 < 0 || c2 >= W || r2 < 0 || r2 >= H || !t.valid(c1, r1) || !t.valid(c2, r2)) return 0.0;
    const double outer = static_cast<double>(t.heights(col, row)) - t.heights(c1, r1);
    const double inner = static_cast<double>(t.heights(c1, r1)) - t.heights(c2, r2);
    if (outer * inner <= 0.0) return 0.0;
    const double gentler = std::abs(outer) < std::abs(inner) ? outer : inner;
    return std::clamp(gentler, -spacing, spacing);
  };
  Terrain out;
  out.heights = Grid<float>(W + left + right, H + top + bottom);
  for (int r = 0; r < H; ++r) std::copy_n(&t.heights(0, r), W, &out.heights(left, r + top));
  auto fill_ring = [&](int c, int r) {
    const int src_c = std::clamp(c - left, 0, W - 1), src_r = std::clamp(r - top, 0, H - 1);
    const int dcol = c - left - src_c, drow = r - top - src_r;
    const float boundary = t.heights(src_c, src_r);
    double z = boundary;
    if (!std::isnan(boundary)) {
      const Jacobian j = t.frame.at(src_c + t.origin_col, src_r + t.origin_row);
      if (dcol != 0) z += rise(src_c, src_r, dcol, 0, std::hypot(j.a, j.c));
      if (drow != 0) z += rise(src_c, src_r, 0, drow, std::hypot(j.b, j.d));
    }
    out.heights(c, r) = static_cast<float>(z);
  };
  for (int c = 0; c < out.width(); ++c) {
    if (top) fill_ring(c, 0);
    if (bottom) fill_ring(c, out.height() - 1);
  }
  for (int r = top; r < top + H; ++r) {
    if (left) fill_ring(0, r);
    if (right) fill_ring(out.width() - 1, r);
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
