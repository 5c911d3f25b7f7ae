#pragma once
// The far field of a tiled run at unlimited radius (docs/tiling.md): each tile's horizons are
// exact within its halo of H metres (the method at --radius H) and, beyond it, come from a
// conservative overview pyramid of the whole raster, every cell of a level the maximum of its
// 2 x 2 children, marched at a level that grows coarser with distance. The two horizons combine
// as their maximum per direction.
#include <cstdint>
#include <memory>
#include <vector>

#include "skyview/core/grid.h"
#include "skyview/raster/terrain.h"
#include "skyview/raster/terrain_reader.h"
#include "skyview/sky_view/sky_view.h"
#include "skyview/tiling/pyramid_file.h"

namespace skyview {

// Max-pooled levels of a raster's heights (relative to its reader's base height), from
// `first_level` (cells of 2^first_level x 2^first_level raster cells) up to one cell.
class OverviewPyramid {
 public:
  // Reads the raster once, a strip of rows at a time (never whole). With `keep_minima` the levels'
  // minima are kept too (min-pooled, for the lowest angles of negative openness).
  OverviewPyramid(const TerrainReader& reader, int first_level, bool keep_minima = false);
  // Pyramid of a terrain already in memory (tests).
  OverviewPyramid(const Terrain& terrain, int first_level, bool keep_minima = false);
  // A pyramid as stored (decode_pyramid checked its sizes).
  explicit OverviewPyramid(PyramidLevels levels) : p_(std::move(levels)) {}

  int first_level() const { return p_.first_level; }
  int last_level() const { return p_.first_level + static_cast<int>(p_.max.size()) - 1; }
  // Level l's maxima (NaN where every cell below is nodata).
  const Grid<float>& level(int l) const { return p_.max[static_cast<std::size_t>(l - p_.first_level)]; }
  // Level l's minima (of the same grown blocks); only where kept.
  bool has_minima() const { return !p_.min.empty(); }
  const Grid<float>& minima(int l) const { return p_.min[static_cast<std::size_t>(l - p_.first_level)]; }
  // The largest relief (maximum less minimum) within one cell of level l, metres.
  double relief(int l) const { return p_.relief[static_cast<std::size_t>(l - p_.first_level)]; }
  // The raster's lowest and highest valid heights (relative to the base height).
  double lowest() const { return p_.lowest; }
  double highest() const { return p_.highest; }
  std::uint64_t bytes() const;
  // Everything it holds, as encode_pyramid stores it.
  const PyramidLevels& levels() const { return p_; }

 private:
  void add_rows(const Grid<float>& heights, int row0, int rows, std::vector<Grid<float>>& minima);
  void build_levels(std::vector<Grid<float>>& minima);
  PyramidLevels p_;
};

// The far field's error, for a halo of H metres on a pyramid (docs/tiling.md derives it).
struct FarFieldBound {
  double angle = 0;           // radians: |horizon angle - exact| in any direction, where both are above 0
  double horizon = 0;         // radians: |horizon angle - exact| in any direction, of any sign (skyview horizon)
  double svf = 0;             // |svf - exact svf| (also svf_surface's, openness in degrees: angle)
  double sky_visibility = 0;  // |sky_visibility - exact|
};

struct FarFieldSettings {
  double halo_m = 0;          // H: the near field's radius
  double cell_m = 1;          // the smallest ground side of a raster cell
  double diagonal_m = 1.414;  // a raster cell's ground diagonal
  double curvature = 0;       // c of the drop c d^2 (the run's, resolved on the whole raster)
  int cells_per_level = 16;   // K: level l is marched from K 2^l cell sides on
};

// The level the march reads first (from the halo on): the coarsest whose cells are at most 1/K of
// the halo, at least 1 and at least the pyramid's first.
int far_field_first_level(const FarFieldSettings& s, int pyramid_first = 1);
FarFieldBound far_field_bound(const OverviewPyramid& pyramid, const FarFieldSettings& s, double raster_diagonal_m);

// The far field of every cell of a tiled run: the march over the pyramid's cells beyond H.
class FarField final : public FarHorizons {
 public:
  // `frame` is the raster's (its Jacobian at the centre sets the rays' pixel steps).
  FarField(std::shared_ptr<const OverviewPyramid> pyramid, const FarFieldSettings& s, const Jacobian& centre,
           int raster_width, int raster_height);
  void raise(const Terrain& terrain, const Window& window, const HorizonField& field, int k,
             float* upper) const override;
  // With the pyramid's minima: the lowest far angle, from each crossed block's minimum at whichever
  // end of the ray's stretch in it gives the lower angle (never above the exact one).
  void lower(const Terrain& terrain, const Window& window, const HorizonField& field, int k,
             float* lower) const override;
  // The tangent of the highest far-field angle from a point at raster pixel (x, y) (cell centres at
  // .5) and height z along azimuth `azimuth`; -inf where the ray meets no valid cell beyond H.
  double far_tangent(double x, double y, double z, double azimuth) const;
  // The tangent of the lowest far-field angle likewise (needs the minima); +inf where none.
  double far_low_tangent(double x, double y, double z, double azimuth) const;
  const FarFieldSettings& settings() const { return s_; }
  const std::shared_ptr<const OverviewPyramid>& pyramid() const { return pyramid_; }

 private:
  // Walks the crossed cells of every level beyond H: visit(level, i, j, entry, exit distance).
  template <class Visit>
  void march(double x, double y, double azimuth, Visit&& visit) const;
  std::shared_ptr<const OverviewPyramid> pyramid_;
  FarFieldSettings s_;
  Jacobian centre_;
  int width_, height_;
};

}  // namespace skyview
