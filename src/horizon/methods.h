#pragma once
// Constructors of the HorizonEngine implementations, one file each; only the factory calls them.
#include <memory>
#include <vector>

#include "skyview/horizon/horizon_engine.h"

namespace skyview::detail {

std::unique_ptr<HorizonEngine> make_sampled_engine(const HorizonParams& params);
std::unique_ptr<HorizonEngine> make_march_engine(const HorizonParams& params);
std::unique_ptr<HorizonEngine> make_sweep_engine(const HorizonParams& params);
std::unique_ptr<HorizonEngine> make_raycast_engine(const HorizonParams& params);

// The march's horizons at the listed cells of a buffer already extended at the raster's edges
// (extend_at_raster_edges), at every row and column crossing to the buffer's edge: exact on the
// surface every method reads, with no radius. `out` holds them as a window of one row, cell i in
// column i, in `directions` uniform sectors rotated by `sector_rotation` (HorizonField). What the svf check (SvfCheck)
// measures runs against.
void exact_horizons_at(const Terrain& extended, const std::vector<CellIndex>& cells, int directions, double curvature,
                       double sector_rotation, HorizonField& out);

}  // namespace skyview::detail
