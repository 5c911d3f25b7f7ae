#include "skyview/sky_view.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace skyview {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
}  // namespace

namespace {

// The sector azimuths' cosines and sines, shared by every cell.
struct Sectors {
  int n;
  double share;  // a sector's share of the full circle, Δ / 2π
  double half;   // sin(Δ / 2)
  std::vector<double> cos_phi, sin_phi;
  explicit Sectors(int n) : n(n), share(1.0 / n), half(std::sin(kPi / n)), cos_phi(n), sin_phi(n) {
    for (int k = 0; k < n; ++k) {
      cos_phi[k] = std::cos(sector_azimuth(k, n));
      sin_phi[k] = std::sin(sector_azimuth(k, n));
    }
  }
};

// What a cell's sectors share: its surface's tilt and the offset of its sectors from the aspect.
struct CellTilt {
  double cb, sb, tb;              // cosine, sine and tangent of the slope
  double cos_offset, sin_offset;  // of rotation - aspect
  CellTilt(double rotation, double slope, double aspect)
      : cb(std::cos(slope)),
        sb(std::sin(slope)),
        tb(std::tan(slope)),
        cos_offset(std::cos(rotation - aspect)),
        sin_offset(std::sin(rotation - aspect)) {}
};

struct SkySums {
  double svf = 0, visibility = 0, surface = 0, openness = 0;
};

// Every quantity of sky_view.h over a cell's sectors (the formulas there). A sector costs one
// sine and cosine of its horizon: the sky starts at H = max(h, t, 0), and the surface's own
// horizon t = atan(-tan β cos(φ - A)) beats the other two only on slopes facing away from the
// sector, where one arctangent gives it. The sector's offset from the aspect comes from the
// angle-sum formula rather than a cosine per sector.
SkySums sky_sums(const float* h, const Sectors& s, const CellTilt& tilt) {
  SkySums sum;
  for (int k = 0; k < s.n; ++k) {
    const double above = std::max(0.0, static_cast<double>(h[k]));
    const double sin_above = std::sin(above), cos_above = std::cos(above);
    sum.svf += sin_above * sin_above;
    sum.visibility += sin_above;
    const double cos_rel = s.cos_phi[k] * tilt.cos_offset - s.sin_phi[k] * tilt.sin_offset;
    const double x = -tilt.tb * cos_rel;  // tangent of the surface's own horizon
    double H = above, sH = sin_above, cH = cos_above;
    if (x * cos_above > sin_above) {
      H = std::atan(x);
      cH = 1.0 / std::sqrt(1.0 + x * x);
      sH = x * cH;
    }
    sum.surface += tilt.cb * cH * cH * s.share + tilt.sb * cos_rel * s.half * (0.5 * kPi - H - sH * cH) / kPi;
    sum.openness += 90.0 - h[k] * 180.0 / kPi;
  }
  return sum;
}

}  // namespace

double svf_horizontal(const float* h, int n) { return 1.0 - sky_sums(h, Sectors(n), CellTilt(0, 0, 0)).svf / n; }

double sky_visibility(const float* h, int n) { return 1.0 - sky_sums(h, Sectors(n), CellTilt(0, 0, 0)).visibility / n; }

double svf_tilted(const float* h, int n, double rotation, double slope, double aspect) {
  return std::clamp(sky_sums(h, Sectors(n), CellTilt(rotation, slope, aspect)).surface, 0.0, 1.0);
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
  const Sectors sectors(n);
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
      double slope = 0, aspect = 0;
      horn_slope_aspect(terrain, col, row, slope, aspect);
      const double rot = field.rotation.empty() ? 0.0 : field.rotation[cell];
      const SkySums sum = sky_sums(up.data(), sectors, CellTilt(rot, slope, aspect));
      p.svf(wc, wr) = static_cast<float>(1.0 - sum.svf / n);
      p.sky_visibility(wc, wr) = static_cast<float>(1.0 - sum.visibility / n);
      p.svf_surface(wc, wr) = static_cast<float>(std::clamp(sum.surface, 0.0, 1.0));
      p.openness_positive(wc, wr) = static_cast<float>(sum.openness / n);
      if (has_lower) {
        double neg = 0.0;
        for (int k = 0; k < n; ++k) neg += 90.0 + field.lower_at(cell, k) * 180.0 / kPi;
        p.openness_negative(wc, wr) = static_cast<float>(neg / n);
      }
    }
  });
  for (unsigned char l : leaves) p.edge_cells += l;
  return p;
}

}  // namespace skyview
