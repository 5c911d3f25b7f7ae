#include "skyview/sky_view.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace skyview {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
}  // namespace

double svf_horizontal(const float* h, int n) {
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const double s = std::sin(std::max(0.0f, h[k]));
    sum += s * s;
  }
  return 1.0 - sum / n;
}

double sky_visibility(const float* h, int n) {
  double sum = 0.0;
  for (int k = 0; k < n; ++k) sum += std::sin(std::max(0.0f, h[k]));
  return 1.0 - sum / n;
}

double svf_tilted(const float* h, int n, double rotation, double slope, double aspect) {
  const double delta = 2.0 * kPi / n;
  const double cb = std::cos(slope), sb = std::sin(slope), tb = std::tan(slope);
  const double half = std::sin(0.5 * delta);
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const double rel = sector_azimuth(k, n) + rotation - aspect;
    const double cos_rel = std::cos(rel);
    const double plane = std::atan(-tb * cos_rel);  // the surface's own horizon in this direction
    // Sky is above the horizontal, above the terrain's horizon and above the surface's plane.
    const double H = std::max({static_cast<double>(h[k]), plane, 0.0});
    const double sH = std::sin(H), cH = std::cos(H);
    sum += cb * cH * cH * delta / (2.0 * kPi) + sb * cos_rel * half * (0.5 * kPi - H - sH * cH) / kPi;
  }
  return std::clamp(sum, 0.0, 1.0);
}

void horn_slope_aspect(const Terrain& t, int col, int row, double& slope, double& aspect) {
  const double z0 = t.heights(col, row);
  auto z = [&](int dc, int dr) -> double {
    const int c = col + dc, r = row + dr;
    if (!t.heights.in_grid(c, r) || !t.valid(c, r)) return z0;
    return t.heights(c, r);
  };
  // Horn (1981): weighted central differences per pixel step.
  const double dz_dcol = ((z(1, -1) + 2 * z(1, 0) + z(1, 1)) - (z(-1, -1) + 2 * z(-1, 0) + z(-1, 1))) / 8.0;
  const double dz_drow = ((z(-1, 1) + 2 * z(0, 1) + z(1, 1)) - (z(-1, -1) + 2 * z(0, -1) + z(1, -1))) / 8.0;
  // Pixel-space gradient = J^T * ground gradient; solve for the east/north gradient.
  const Jacobian j = t.frame.at(col + t.origin_col, row + t.origin_row);
  const double det = j.a * j.d - j.b * j.c;
  const double g_east = (j.d * dz_dcol - j.c * dz_drow) / det;
  const double g_north = (-j.b * dz_dcol + j.a * dz_drow) / det;
  const double g = std::hypot(g_east, g_north);
  slope = std::atan(g);
  aspect = g > 0.0 ? std::atan2(-g_east, -g_north) : 0.0;
}

bool search_circle_leaves_raster(const Terrain& t, int col, int row, double radius) {
  if (std::isinf(radius)) return true;
  const Jacobian j = t.frame.at(col + t.origin_col, row + t.origin_row);
  const double det = j.a * j.d - j.b * j.c;
  // Half-extent, in pixels, of the image of a ground circle under the inverse Jacobian.
  const double half_cols = radius * std::hypot(j.d, j.b) / std::abs(det);
  const double half_rows = radius * std::hypot(j.c, j.a) / std::abs(det);
  const double gc = col + t.origin_col, gr = row + t.origin_row;
  return gc - half_cols < 0 || gr - half_rows < 0 || gc + half_cols > t.full_width - 1 ||
         gr + half_rows > t.full_height - 1;
}

SkyViewProducts sky_view_products(const Terrain& terrain, const Window& window, const HorizonField& field,
                                  double radius, EdgeMode edge) {
  SkyViewProducts p;
  const int w = window.cols, h = window.rows;
  p.svf = p.svf_surface = p.sky_visibility = p.openness_positive = p.openness_negative = Grid<float>(w, h, kNaN);
  const int n = field.directions;
  const bool has_lower = !field.lower.empty();
  std::vector<unsigned char> leaves(static_cast<std::size_t>(w) * h, 0);
  tbb::parallel_for(0, h, [&](int wr) {
    const int row = window.row0 + wr;
    std::vector<float> up(static_cast<std::size_t>(n));  // one cell's horizons, gathered from the planes
    for (int wc = 0; wc < w; ++wc) {
      const int col = window.col0 + wc;
      const std::size_t cell = field.cell(wc, wr);
      if (!terrain.valid(col, row)) continue;
      if (search_circle_leaves_raster(terrain, col, row, radius)) {
        leaves[cell] = 1;
        if (edge == EdgeMode::nodata) continue;
      }
      for (int k = 0; k < n; ++k) up[k] = field.upper_at(cell, k);
      p.svf(wc, wr) = static_cast<float>(svf_horizontal(up.data(), n));
      p.sky_visibility(wc, wr) = static_cast<float>(sky_visibility(up.data(), n));
      double slope = 0, aspect = 0;
      horn_slope_aspect(terrain, col, row, slope, aspect);
      const double rot = field.rotation.empty() ? 0.0 : field.rotation[cell];
      p.svf_surface(wc, wr) = static_cast<float>(svf_tilted(up.data(), n, rot, slope, aspect));
      double pos = 0.0, neg = 0.0;
      for (int k = 0; k < n; ++k) pos += 90.0 - up[k] * 180.0 / kPi;
      p.openness_positive(wc, wr) = static_cast<float>(pos / n);
      if (has_lower) {
        for (int k = 0; k < n; ++k) neg += 90.0 + field.lower_at(cell, k) * 180.0 / kPi;
        p.openness_negative(wc, wr) = static_cast<float>(neg / n);
      }
    }
  });
  for (unsigned char l : leaves) p.edge_cells += l;
  return p;
}

}  // namespace skyview
