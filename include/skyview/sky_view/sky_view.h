#pragma once
// Sky-view quantities from per-direction horizon angles. Each sector k of width Δ = 2π/N
// around azimuth φ_k holds a constant horizon h_k, and every quantity is integrated exactly
// over each sector (formulas and peer-tool definitions in docs/sky_view.md):
//   svf            = 1 - (1/N) Σ sin²(max(h_k, 0))              cosine-weighted, horizontal surface
//   sky_visibility = 1 - (1/N) Σ sin(max(h_k, 0))               solid-angle fraction (paper's Eq. 5)
//   svf_surface    = Σ [cosβ cos²H_k Δ/2π + sinβ cos(φ_k-A) sin(Δ/2) (π/2 - H_k - sinH_k cosH_k)/π]
//                    with H_k = max(h_k, t_k, 0), t_k the surface plane's own horizon
//   openness_positive = mean(90° - h_k), openness_negative = mean(90° + lowest angle_k)  (Yokoyama 2002)
// Where the sectors are uneven (AzimuthSpacing::grid_lines) each sector's term weighs its own share
// Δ_k / 2π instead of 1/N (HorizonField::sectors, DirectionSet::share).
#include <memory>
#include <string>
#include <vector>

#include "skyview/core/grid.h"
#include "skyview/horizon/horizon_engine.h"

namespace skyview {

// One cell's values from n uniform sectors (the sums over a field read its own sectors).
double svf_horizontal(const float* horizons, int n);
double sky_visibility(const float* horizons, int n);
// slope β (radians) and aspect A (azimuth of steepest descent, radians); `rotation` offsets φ_k.
double svf_tilted(const float* horizons, int n, double rotation, double slope, double aspect);

// Slope and downslope azimuth of a cell by Horn's method on true ground distances; where a
// neighbour is nodata or off the raster, its differences are taken one-sided or left out.
void horn_slope_aspect(const Terrain& terrain, int col, int row, double& slope, double& aspect);

enum class EdgeMode { open, nodata };

struct SkyViewProducts {
  Grid<float> svf, svf_surface, sky_visibility, openness_positive, openness_negative;
  std::int64_t edge_cells = 0;  // cells whose search circle leaves the raster
  // The Monte-Carlo svf and its standard error where the method estimates svf directly (raycast
  // with rays, HorizonField::svf_direct); empty otherwise.
  Grid<float> svf_montecarlo, svf_montecarlo_stderr;
};

// True where the ground circle of `radius` metres around the cell leaves the full raster.
bool search_circle_leaves_raster(const Terrain& terrain, int col, int row, double radius);

// The products a run keeps. Grids of the others may be left empty, and SkyViewSums holds no sums
// for them: a run that writes svf alone keeps 8 bytes per cell where all five keep 64.
enum class Product : unsigned {
  svf = 1,
  svf_surface = 2,
  sky_visibility = 4,
  openness_positive = 8,
  openness_negative = 16
};
// Each product's grid in SkyViewProducts.
struct ProductGrid {
  Product product;
  Grid<float> SkyViewProducts::*grid;
};
inline constexpr ProductGrid kProductGrids[] = {{Product::svf, &SkyViewProducts::svf},
                                                {Product::svf_surface, &SkyViewProducts::svf_surface},
                                                {Product::sky_visibility, &SkyViewProducts::sky_visibility},
                                                {Product::openness_positive, &SkyViewProducts::openness_positive},
                                                {Product::openness_negative, &SkyViewProducts::openness_negative}};

inline Grid<float> SkyViewProducts::*product_grid(Product p) {
  for (const ProductGrid& g : kProductGrids) {
    if (g.product == p) return g.grid;
  }
  return nullptr;
}

class ProductSet {
 public:
  static ProductSet all() { return ProductSet(31); }
  static ProductSet none() { return ProductSet(0); }
  bool has(Product p) const { return (bits_ & static_cast<unsigned>(p)) != 0; }
  ProductSet& add(Product p) {
    bits_ |= static_cast<unsigned>(p);
    return *this;
  }

 private:
  explicit ProductSet(unsigned bits) : bits_(bits) {}
  unsigned bits_;
};

// The products summed direction by direction, so that a method that finds one direction at a time
// (HorizonEngine::compute_directions) need not keep every direction's horizons: per cell, a running
// sum (8 bytes) for each product kept, and for svf_surface the surface's tilt (24 bytes more),
// whatever the number of directions.
class SkyViewSums {
 public:
  // Memory per cell of the window: 64 bytes for all five products.
  static int bytes_per_cell(ProductSet keep);

  SkyViewSums(const Terrain& terrain, const Window& window, int directions, ProductSet keep = ProductSet::all());
  ~SkyViewSums();
  SkyViewSums(const SkyViewSums&) = delete;
  SkyViewSums& operator=(const SkyViewSums&) = delete;
  // Directions [first, first + count), added in order from direction 0: their planes of horizon
  // angles (window-sized, row-major, one after another), their lowest angles likewise (or null,
  // for every batch), and the field they come from, for its rotations of the direction set
  // (HorizonField::cell_rotation; its planes are not read).
  void add(int first, int count, const float* upper, const float* lower, const HorizonField& rotations);
  // The kept products (the others' grids empty); openness_negative is NaN unless lowest angles
  // were added.
  SkyViewProducts finish(double radius, EdgeMode edge) const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

// Products for the cells of `window`; `field` must come from that window. Openness bands are
// NaN when the field has no lower horizons. The same sums as SkyViewSums, in one batch.
SkyViewProducts sky_view_products(const Terrain& terrain, const Window& window, const HorizonField& field,
                                  double radius, EdgeMode edge);

// Horizons from beyond a method's radius (a tiled run's far field, docs/tiling.md): raises the
// upper angles of direction k of `window`'s cells in place. Products raised by it count every
// cell's search as unlimited (the radius is the far field's).
class FarHorizons {
 public:
  virtual ~FarHorizons() = default;
  // `upper` is direction k's plane over `window` (row-major, window-sized); `field` gives the
  // sectors' azimuths (HorizonField::azimuth).
  virtual void raise(const Terrain& terrain, const Window& window, const HorizonField& field, int k,
                     float* upper) const = 0;
  // Lowers direction k's lowest angles (`lower`, laid out as `upper`) by the terrain beyond the
  // method's radius, for negative openness; by default they stay the method's.
  virtual void lower(const Terrain& /*terrain*/, const Window& /*window*/, const HorizonField& /*field*/, int /*k*/,
                     float* /*lower*/) const {}
};

// The products of `window`'s cells straight from a method, so that memory does not grow with the
// number of directions: a method that finds one direction at a time (the sweep) hands them over as
// they are done, summed by SkyViewSums once its whole field would take twice what the sums take;
// the others compute the window in blocks of rows holding about `horizon_bytes` of horizons each.
// The products in `keep` are the same bits as sky_view_products over the whole field (tested);
// the others' grids may be empty. Progress advances by the window's cells.
SkyViewProducts compute_sky_view(const HorizonEngine& engine, const Terrain& terrain, const Window& window,
                                 EdgeMode edge, ProgressCounter& progress,
                                 std::size_t horizon_bytes = kHorizonBlockBytes, ProductSet keep = ProductSet::all(),
                                 const FarHorizons* far = nullptr);

}  // namespace skyview
