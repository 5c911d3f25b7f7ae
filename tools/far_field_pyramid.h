#pragma once
// Where a tiled run's far-field pyramid comes from (docs/tiling.md): built once from the raster, or
// read from a --tiles-dir's far_field_pyramid.bin that an earlier run of the same input left there;
// under mpirun rank 0 makes it and sends it to the other ranks (MPI_Bcast), which never read the
// raster whole.
#include <memory>

#include "skyview/tiling/far_field.h"
#include "skyview/tiling/tile_manifest.h"

namespace skyview::cli {

struct HorizonJob;

// The file's name in the tiles folder.
inline constexpr const char* kPyramidFileName = "far_field_pyramid.bin";

// The pyramid of the job's raster from `first_level` on, with its minima where `minima` (negative
// openness). A kept file that is damaged or foreign is built again (with a warning); one of another
// input or first level, or without the minima asked for, is built again silently. Sets
// job.tiles.pyramid_reused on rank 0 where it was read from the folder.
std::shared_ptr<const OverviewPyramid> run_pyramid(HorizonJob& job, int first_level, bool minima);

// Rank 0 of a --tiles-dir run at unlimited radius, once the manifest is the run's: writes the
// pyramid into the folder (unless it was read from there) and records it in `manifest`. Returns
// whether it did (false for runs without a far field).
bool keep_run_pyramid(const HorizonJob& job, TileManifest& manifest);

}  // namespace skyview::cli
