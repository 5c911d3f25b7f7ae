#pragma once
// Constructors of the HorizonEngine implementations, one file each; only the factory calls them.
#include <memory>
#include <vector>

#include "skyview/horizon/horizon_engine.h"
#include "skyview/horizon/point_horizons.h"

namespace skyview::detail {

std::unique_ptr<HorizonEngine> make_sampled_engine(const HorizonParams& params);
std::unique_ptr<HorizonEngine> make_march_engine(const HorizonParams& params);
std::unique_ptr<HorizonEngine> make_sweep_engine(const HorizonParams& params);
std::unique_ptr<HorizonEngine> make_raycast_engine(const HorizonParams& params);

// The march's horizons at the listed cells of a buffer already extended at the raster's edges
// (extend_at_raster_edges), at every row and column crossing to the raster's extent: exact on the
// surface every method reads, with no radius. `out` holds them as a window of one row, cell i in
// column i, in `directions` uniform sectors rotated by `sector_rotation` (HorizonField). What the svf check (SvfCheck)
// measures runs against.
void exact_horizons_at(const Terrain& extended, const std::vector<CellIndex>& cells, int directions, double curvature,
                       double sector_rotation, HorizonField& out);

// An eye for point queries: a pixel position in a buffer and its height in the buffer's units
// (relative to Terrain::base_height); NaN height: skip it.
struct EyePoint {
  double col = 0, row = 0, z = 0;
};

// Horizons of eyes on a buffer already extended at the raster's edges, [eye * directions + k], along
// `directions` uniform sectors turned by `sector_rotation`: the march's walk from each eye
// (RayScanner::scan_from) to `radius` metres (infinity: the raster's extent) with curvature c, and with
// `rising` each direction's RisingSteps.
void march_point_horizons(const Terrain& extended, const std::vector<EyePoint>& eyes, int directions,
                          double sector_rotation, double radius, double curvature, bool early_exit,
                          std::vector<float>& out, std::vector<std::vector<std::vector<RisingStep>>>* rising,
                          ProgressCounter* progress);

// The same by the ray cast (no curvature; with a radius, rays stop at it).
void raycast_point_horizons(const Terrain& extended, const std::vector<EyePoint>& eyes, int directions,
                            double sector_rotation, double radius, std::vector<float>& out, ProgressCounter* progress);

}  // namespace skyview::detail
