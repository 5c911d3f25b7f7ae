#include "horizon/sweep_geometry.h"

#include "horizon/track_box.h"
#include "skyview/raster/ground_frame.h"

namespace skyview::detail::sweep {

SweepGeometry make_geometry(const Terrain& terrain, const float* transposed, double azimuth) {
  SweepGeometry g;
  const int W = terrain.width(), H = terrain.height();
  // Every tile and block of a raster gets the same lines; and a direction set rotated to grid north
  // (direction_set_rotation) puts its axes exactly on rows and columns.
  const Jacobian j = raster_centre_jacobian(terrain);
  double pc, pr;
  j.pixel_step_for_azimuth(azimuth, pc, pr);
  const double se = std::sin(azimuth), cn = std::cos(azimuth);
  const double t_col = j.a * se + j.c * cn, t_row = j.b * se + j.d * cn;
  g.by_rows = std::abs(pr) >= std::abs(pc);
  g.major_n = g.by_rows ? H : W;
  g.minor_n = g.by_rows ? W : H;
  g.k = g.by_rows ? pc / pr : pr / pc;
  // Along an axis or a diagonal of square cells, keep lines exactly on cell centres and corners:
  // a drift of 1 - 1e-16 per step would put a minor crossing a rounding error from every sample.
  // A drift off that adds up to under 1e-4 cell over the whole raster is such a residue, not a
  // direction (the grid diagonals of a set rotated to grid north come out 1e-9 off, from the
  // frame's numerical Jacobian), and far below what one Jacobian for the raster already neglects.
  const double residue = 1e-4 / std::max(1, g.by_rows ? terrain.raster_height() : terrain.raster_width());
  if (std::abs(g.k) < residue) g.k = 0.0;
  if (std::abs(std::abs(g.k) - 1.0) < residue) g.k = std::copysign(1.0, g.k);
  // Half slopes: the grid lines' (1, 2) steps, or a uniform set's 45° on cells twice as long as wide.
  if (std::abs(std::abs(g.k) - 0.5) < residue) g.k = std::copysign(0.5, g.k);
  g.t_major = g.by_rows ? t_row : t_col;
  g.t_minor = g.by_rows ? t_col : t_row;
  g.toward = (g.by_rows ? pr < 0 : pc < 0) ? -1 : 1;  // the viewer looks towards index 0 when -1
  g.t_step = std::abs(g.t_major) + g.k * g.toward * g.t_minor;
  g.k_step = g.k * g.toward;
  // Lines that advance by columns read the transposed copy, so every line read is contiguous.
  g.z = g.by_rows ? terrain.heights.data() : transposed;
  g.major_stride = g.by_rows ? W : H;
  const TrackBox box = track_box(terrain);
  g.major_lo = g.by_rows ? box.row_lo : box.col_lo;
  g.major_hi = g.by_rows ? box.row_hi : box.col_hi;
  g.minor_lo = g.by_rows ? box.col_lo : box.row_lo;
  g.minor_hi = g.by_rows ? box.col_hi : box.row_hi;
  return g;
}

std::vector<NearCrossing> near_crossings(const SweepGeometry& g, int near_steps, double radius, double c) {
  std::vector<NearCrossing> out;
  for (int s = 1; s <= near_steps; ++s) {
    const double off = s * g.k_step;
    double q;
    if (crossing_between((s - 1) * g.k_step, off, q)) {
      const double lambda = (q - (s - 1) * g.k_step) / g.k_step;
      const double d = (s - 1 + lambda) * g.t_step;
      const int qi = static_cast<int>(q);
      if (d <= radius)
        out.push_back({s - 1, qi, s, qi, static_cast<float>(lambda), static_cast<float>(1.0 / d),
                       static_cast<float>(c * d), s - 1 + lambda, q});
    }
    const double d = s * g.t_step;
    const int i_off = static_cast<int>(std::floor(off));
    const double f = off - i_off;
    // With no fraction the neighbour is not read: a NaN there would poison w * (p1 - p0).
    if (d <= radius)
      out.push_back({s, i_off, s, f > 0.0 ? i_off + 1 : i_off, static_cast<float>(f), static_cast<float>(1.0 / d),
                     static_cast<float>(c * d), static_cast<double>(s), off});
  }
  return out;
}

}  // namespace skyview::detail::sweep
