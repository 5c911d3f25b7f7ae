#include "skyview/tiling/far_field.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

namespace skyview {

namespace {

// Rows of the raster read at a time while the pyramid is built: about 64 MB of the reader's
// buffers (13 bytes a cell), whole cells of the first level.
int strip_rows(int width, int block) {
  const int rows = std::max(1, static_cast<int>((std::int64_t{64} << 20) / (13 * std::int64_t{std::max(1, width)})));
  return std::max(block, rows / block * block);
}

int cells_at(int n, int level) { return static_cast<int>((static_cast<std::int64_t>(n) + (1 << level) - 1) >> level); }

}  // namespace

OverviewPyramid::OverviewPyramid(const TerrainReader& reader, int first_level, bool keep_minima) {
  p_.first_level = std::max(1, first_level);
  p_.width = reader.width();
  p_.height = reader.height();
  std::vector<Grid<float>> minima;
  const int step = strip_rows(p_.width, 1 << p_.first_level);
  for (int row0 = 0; row0 < p_.height; row0 += step) {
    const int rows = std::min(step, p_.height - row0);
    const Terrain strip = reader.read({0, row0, p_.width, rows});
    add_rows(strip.heights, row0, rows, minima);
  }
  build_levels(minima);
  if (keep_minima) p_.min = std::move(minima);
}

OverviewPyramid::OverviewPyramid(const Terrain& terrain, int first_level, bool keep_minima) {
  p_.first_level = std::max(1, first_level);
  p_.width = terrain.width();
  p_.height = terrain.height();
  std::vector<Grid<float>> minima;
  add_rows(terrain.heights, 0, p_.height, minima);
  build_levels(minima);
  if (keep_minima) p_.min = std::move(minima);
}

// Each raster cell raises the maximum (and lowers the minimum) of every first-level cell whose
// block, grown by one raster cell on each side, holds it: the surface between cell centres
// (the mesh every method reads) within a block is then bounded by the block's extremes.
void OverviewPyramid::add_rows(const Grid<float>& heights, int row0, int rows, std::vector<Grid<float>>& minima) {
  const int b = 1 << p_.first_level;
  const int w = cells_at(p_.width, p_.first_level), h = cells_at(p_.height, p_.first_level);
  if (p_.max.empty()) {
    p_.max.emplace_back(w, h, NAN);
    minima.emplace_back(w, h, NAN);
  }
  Grid<float>& hi = p_.max.front();
  Grid<float>& lo = minima.front();
  // The blocks whose grown extent holds cell n: k - 1 where n is a block's first cell, k + 1
  // where it is its last.
  auto blocks = [b](int n, int cells, int& first, int& last) {
    const int k = n / b, m = n % b;
    first = std::max(0, m == 0 ? k - 1 : k);
    last = std::min(cells - 1, m == b - 1 ? k + 1 : k);
  };
  for (int r = 0; r < rows; ++r) {
    int j0, j1;
    blocks(row0 + r, h, j0, j1);
    for (int c = 0; c < p_.width; ++c) {
      const float z = heights(c, r);
      if (std::isnan(z)) continue;
      p_.lowest = std::min(p_.lowest, static_cast<double>(z));
      p_.highest = std::max(p_.highest, static_cast<double>(z));
      int i0, i1;
      blocks(c, w, i0, i1);
      for (int j = j0; j <= j1; ++j) {
        for (int i = i0; i <= i1; ++i) {
          float& up = hi(i, j);
          float& down = lo(i, j);
          if (std::isnan(up) || z > up) up = z;
          if (std::isnan(down) || z < down) down = z;
        }
      }
    }
  }
}

void OverviewPyramid::build_levels(std::vector<Grid<float>>& minima) {
  auto relief_of = [](const Grid<float>& hi, const Grid<float>& lo) {
    double r = 0;
    for (std::size_t i = 0; i < hi.size(); ++i) {
      if (!std::isnan(hi.data()[i])) r = std::max(r, static_cast<double>(hi.data()[i] - lo.data()[i]));
    }
    return r;
  };
  p_.relief.push_back(relief_of(p_.max.back(), minima.back()));
  while (p_.max.back().width() > 1 || p_.max.back().height() > 1) {
    const Grid<float>& hi = p_.max.back();
    const Grid<float>& lo = minima.back();
    const int w = (hi.width() + 1) / 2, h = (hi.height() + 1) / 2;
    Grid<float> up(w, h, NAN), down(w, h, NAN);
    for (int j = 0; j < h; ++j) {
      for (int i = 0; i < w; ++i) {
        for (int dj = 0; dj < 2; ++dj) {
          for (int di = 0; di < 2; ++di) {
            const int c = 2 * i + di, r = 2 * j + dj;
            if (c >= hi.width() || r >= hi.height() || std::isnan(hi(c, r))) continue;
            if (std::isnan(up(i, j)) || hi(c, r) > up(i, j)) up(i, j) = hi(c, r);
            if (std::isnan(down(i, j)) || lo(c, r) < down(i, j)) down(i, j) = lo(c, r);
          }
        }
      }
    }
    p_.relief.push_back(relief_of(up, down));
    p_.max.push_back(std::move(up));
    minima.push_back(std::move(down));
  }
}

std::uint64_t OverviewPyramid::bytes() const {
  std::uint64_t n = 0;
  for (const Grid<float>& g : p_.max) n += g.size() * sizeof(float);
  for (const Grid<float>& g : p_.min) n += g.size() * sizeof(float);
  return n;
}

namespace {

// Where level l's march begins: K 2^l cell sides, or the halo for the first level.
double level_start(const FarFieldSettings& s, int level, int first) {
  return level == first ? s.halo_m : s.cells_per_level * std::ldexp(s.cell_m, level);
}

}  // namespace

int far_field_first_level(const FarFieldSettings& s, int pyramid_first) {
  int l = std::max(1, pyramid_first);
  while (s.cells_per_level * std::ldexp(s.cell_m, l + 1) <= s.halo_m) ++l;
  return l;
}

FarFieldBound far_field_bound(const OverviewPyramid& pyramid, const FarFieldSettings& s, double raster_diagonal_m) {
  FarFieldBound b;
  if (!(pyramid.highest() > pyramid.lowest())) return b;  // flat: nothing beyond the halo rises
  // No terrain beyond H rises above atan(t) (heights within the raster's range, drop >= 0).
  const double t = (pyramid.highest() - pyramid.lowest()) / s.halo_m;
  const double crude = std::atan(t);
  // A far angle read from level l at entry distance d (>= the level's start) differs from the
  // exact one along the same ray by at most (relief + c (2 d l + l^2) + l t) / d, l the block's
  // diagonal (docs/tiling.md).
  double refined = 0, below = 0;
  const int first = far_field_first_level(s, pyramid.first_level());
  for (int l = first; l <= pyramid.last_level(); ++l) {
    const double d = level_start(s, l, first);
    if (d >= raster_diagonal_m) break;
    const double diag = std::ldexp(s.diagonal_m, l);
    refined = std::max(refined, (pyramid.relief(l) + s.curvature * (2 * d * diag + diag * diag) + diag * t) / d);
    // Below the horizontal the block's entry distance can also make the far angle too low: by at
    // most the block's length times |dh/dd| <= (R + c d'^2) / d^2, d' <= d + diag.
    below = std::max(below, diag * (t + s.curvature * (1 + diag / d) * (1 + diag / d) * d) / d);
  }
  b.angle = std::min(crude, refined);
  b.horizon = std::max(refined, below);
  // Both horizons lie in [0, atan t] where they differ in these bands (max(h, 0)): the sine
  // squared moves by at most sin(2 h) dh there, the sine by at most dh.
  b.svf = std::min(std::sin(crude) * std::sin(crude), std::sin(std::min(2 * crude, M_PI / 2)) * b.angle);
  b.sky_visibility = std::min(std::sin(crude), b.angle);
  return b;
}

FarField::FarField(std::shared_ptr<const OverviewPyramid> pyramid, const FarFieldSettings& s, const Jacobian& centre,
                   int raster_width, int raster_height)
    : pyramid_(std::move(pyramid)), s_(s), centre_(centre), width_(raster_width), height_(raster_height) {}

template <class Visit>
void FarField::march(double x0, double y0, double azimuth, Visit&& visit) const {
  double ux = 0, uy = 0;  // pixels per metre along the ray
  centre_.pixel_step_for_azimuth(azimuth, ux, uy);
  const OverviewPyramid& p = *pyramid_;
  const int first = far_field_first_level(s_, p.first_level());
  // Where the ray leaves the raster: a level's last row and column of cells reach past its edge,
  // and their extremes stand for terrain the ray never passes over (which the bound does not cover).
  const double t_exit = std::min(ux > 0 ? (width_ - x0) / ux : (ux < 0 ? -x0 / ux : INFINITY),
                                 uy > 0 ? (height_ - y0) / uy : (uy < 0 ? -y0 / uy : INFINITY));
  for (int l = first; l <= p.last_level(); ++l) {
    const Grid<float>& g = p.level(l);
    const double size = std::ldexp(1.0, l);  // raster cells per level cell
    const double t_a = level_start(s_, l, first);
    if (t_a >= t_exit) return;
    const double t_b = std::min(t_exit, l == p.last_level() ? INFINITY : level_start(s_, l + 1, first));
    // An exact walk over the level's cells the ray crosses in [t_a, t_b) (Amanatides and Woo).
    const double px = (x0 + ux * t_a) / size, py = (y0 + uy * t_a) / size;
    int i = static_cast<int>(std::floor(px)), j = static_cast<int>(std::floor(py));
    const int si = ux > 0 ? 1 : (ux < 0 ? -1 : 0), sj = uy > 0 ? 1 : (uy < 0 ? -1 : 0);
    const double dx = si != 0 ? size / std::abs(ux) : INFINITY, dy = sj != 0 ? size / std::abs(uy) : INFINITY;
    double next_x = si > 0 ? t_a + (i + 1 - px) * dx : (si < 0 ? t_a + (px - i) * dx : INFINITY);
    double next_y = sj > 0 ? t_a + (j + 1 - py) * dy : (sj < 0 ? t_a + (py - j) * dy : INFINITY);
    double t = t_a;
    while (t < t_b) {
      // Left the raster: no way back along a straight ray.
      if ((i < 0 && si <= 0) || (j < 0 && sj <= 0) || (i >= g.width() && si >= 0) || (j >= g.height() && sj >= 0))
        return;
      const double out = std::min({next_x, next_y, t_b});  // where the ray leaves this cell
      if (i >= 0 && j >= 0 && i < g.width() && j < g.height()) visit(l, i, j, t, out);
      if (next_x < next_y) {
        t = next_x, next_x += dx, i += si;
      } else {
        t = next_y, next_y += dy, j += sj;
      }
    }
  }
}

double FarField::far_tangent(double x0, double y0, double z0, double azimuth) const {
  double best = -std::numeric_limits<double>::infinity();
  const double c = s_.curvature;
  march(x0, y0, azimuth, [&](int l, int i, int j, double t, double) {
    const float z = pyramid_->level(l)(i, j);
    if (!std::isnan(z)) best = std::max(best, (z - z0 - c * t * t) / t);
  });
  return best;
}

double FarField::far_low_tangent(double x0, double y0, double z0, double azimuth) const {
  double lowest = std::numeric_limits<double>::infinity();
  const double c = s_.curvature;
  // (m - z0)/d - c d is concave in d below z0 and falls with d above it: its least over the
  // ray's stretch in a block is at one of the stretch's ends.
  march(x0, y0, azimuth, [&](int l, int i, int j, double t, double out) {
    const float m = pyramid_->minima(l)(i, j);
    if (std::isnan(m)) return;
    lowest = std::min({lowest, (m - z0 - c * t * t) / t, (m - z0 - c * out * out) / out});
  });
  return lowest;
}

namespace {

// Each valid cell of the window's plane k moved by the far field: `toward(h, cell's position,
// height, azimuth)` gives its new angle.
template <class Toward>
void move_plane(const Terrain& terrain, const Window& window, const HorizonField& field, int k, float* plane,
                Toward toward) {
  tbb::parallel_for(0, window.rows, [&](int wr) {
    for (int wc = 0; wc < window.cols; ++wc) {
      const std::size_t cell = static_cast<std::size_t>(wr) * window.cols + wc;
      float& h = plane[cell];
      if (std::isnan(h)) continue;
      const int col = window.col0 + wc, row = window.row0 + wr;
      h = toward(h, col + terrain.origin_col + 0.5, row + terrain.origin_row + 0.5, terrain.heights(col, row),
                 field.azimuth(cell, k));
    }
  });
}

}  // namespace

void FarField::raise(const Terrain& terrain, const Window& window, const HorizonField& field, int k,
                     float* upper) const {
  move_plane(terrain, window, field, k, upper, [this](float h, double x, double y, double z, double azimuth) {
    const double tangent = far_tangent(x, y, z, azimuth);
    return tangent > -INFINITY ? std::max(h, static_cast<float>(std::atan(tangent))) : h;
  });
}

void FarField::lower(const Terrain& terrain, const Window& window, const HorizonField& field, int k,
                     float* lower) const {
  if (!pyramid_->has_minima()) return;
  move_plane(terrain, window, field, k, lower, [this](float h, double x, double y, double z, double azimuth) {
    const double tangent = far_low_tangent(x, y, z, azimuth);
    return tangent < INFINITY ? std::min(h, static_cast<float>(std::atan(tangent))) : h;
  });
}

}  // namespace skyview
