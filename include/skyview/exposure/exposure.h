#pragma once
// The solar exposure of every cell of a DSM over a period (skyview exposure; docs/exposure.md):
// what reaches each cell's own tilted surface (normal by Horn's method, as svf_surface) and a
// horizontal surface at the cell, split into the sun's beam, the sky and the light reflected by
// the ground and surrounding surfaces, with the cell's sky-view factor.
//
// - fast: the Section 6 sampler (exposure_sampler.h) over the exposure map, per horizon direction.
// - exact: the sun's beam of every time step against the cell's horizon interpolated at the sun's
//   azimuth (or an Embree shadow ray, `shadow_rays`), and the sky's radiance, summed over the
//   period, integrated over the visible sky at the map's full resolution with the exact cosine.
// Both read horizons from one engine a direction (or a block of rows) at a time, so memory does
// not grow with the number of directions.
#include <memory>
#include <optional>
#include <vector>

#include "skyview/core/grid.h"
#include "skyview/core/progress.h"
#include "skyview/exposure/sun_horizon.h"
#include "skyview/horizon/horizon_engine.h"
#include "skyview/sky/exposure_map.h"
#include "skyview/sky/exposure_sampler.h"
#include "skyview/sky_view/sky_view.h"

namespace skyview {

enum class ExposureMethod { fast, exact };
const char* exposure_method_name(ExposureMethod method);  // "fast", "exact"

// The sky of the period: its map and, for the exact method, the sun of every step.
struct ExposureSky {
  ExposureMap map{1, 1};
  std::vector<SunStep> sun;  // sun_steps(model, steps); needed by the exact method only
};

struct ExposureRequest {
  ExposureMethod method = ExposureMethod::fast;
  SamplerOptions sampler;  // fast: how the map is read
  // Ground albedo for the reflected term: `albedo` everywhere, or per cell from `albedo_grid`
  // (the window's size; NaN leaves the cell's reflected light and total as nodata).
  double albedo = 0.2;
  Grid<float> albedo_grid;
  // Cells whose search circle leaves the raster: computed as if the terrain beyond did not
  // occlude (open) or left as nodata.
  EdgeMode edge = EdgeMode::open;
  // Horizons held at a time by engines that find all of a cell's directions together.
  std::size_t horizon_bytes = kHorizonBlockBytes;
  // A tiled run at unlimited radius: raises the engine's horizons (within the halo) by the far
  // field beyond it (docs/tiling.md); every cell's search then counts as unlimited.
  std::shared_ptr<const FarHorizons> far_field;
};

// Wh/m² over the period (NaN on nodata cells).
struct ExposureBands {
  Grid<float> total, direct, diffuse, reflected;  // on the cell's tilted surface; total = the three
  Grid<float> horizontal_total;                   // on a horizontal surface at the cell, reflected included
  Grid<float> svf;                                // cosine-weighted, horizontal (as skyview svf's band 1)
  double global_horizontal = 0.0;                 // the map's unobstructed global horizontal exposure
  std::int64_t albedo_nodata_cells = 0;           // cells whose albedo was nodata
  std::int64_t edge_cells = 0;                    // cells whose search circle leaves the raster
};

// Exposure of the cells of `window` (a Terrain buffer's coordinates) from `engine`'s horizons,
// which must run in uniform directions. Progress advances as the engine's does. Throws
// skyview::Error for a request the method cannot serve (exact without sun steps, grid-line
// directions, an albedo grid of another size).
ExposureBands compute_exposure(const HorizonEngine& engine, const Terrain& terrain, const Window& window,
                               const ExposureSky& sky, const ExposureRequest& request, ProgressCounter& progress);

}  // namespace skyview
