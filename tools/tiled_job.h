#pragma once
// Runs of `skyview svf`, `horizon` and `exposure` tile by tile (docs/tiling.md): with --tile-size, or
// when the whole run would take more memory than --memory-limit. Each tile's window plus a halo as
// wide as the search radius is read through GDAL (never the whole raster), computed by the same job
// code as a whole run, and only the tile's own cells are written.
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "skyview/core/progress.h"
#include "skyview/raster/band_writer.h"
#include "skyview/raster/terrain.h"
#include "skyview/tiling/memory_budget.h"

namespace skyview::cli {

struct HorizonJob;

struct TilingOptions {
  int tile_size = 0;         // cells; 0: only where memory asks for tiles
  std::string memory_limit;  // "8G"; empty: the memory available now
  std::string tiles_dir;     // one GeoTIFF per tile here and a VRT at the output; empty: one raster
  const CLI::App* app = nullptr;
};
void add_tiling_options(CLI::App& app, TilingOptions& o);

// What a command tells the job about tiling: its options and the memory its run takes.
struct TileRequest {
  TilingOptions options;
  std::function<MemoryModel(const HorizonEngine&)> memory;
  // The command computes the far field beyond the halo (far_field_job.h), so tiles need no finite
  // --radius.
  bool far_field = false;
  double far_error = -1;  // --far-field-error: the far field's svf bound; < 0: --max-error's, or the default
};

// How a run goes: whole, or by tiles of `tile_size` cells read with `halo` cells around them.
struct TilePlan {
  bool tiled = false;
  int tile_size = 0, halo = 0, tiles = 0;
  int skipped = 0;                   // tiles a --tiles-dir rerun found finished
  std::uint64_t limit = 0;           // bytes (--memory-limit, or what was available)
  bool far_field = false;            // the halo is the far field's (far_field_job.h), not --radius
  double halo_m = 0;                 // the far field's halo in metres (else the engine's radius)
  std::uint64_t reserved = 0;        // bytes of the limit held for the whole run (the far field's pyramid)
  std::uint64_t whole_estimate = 0;  // bytes the whole run would take by the memory model
  std::string why;                   // "--tile-size 64", "the whole run needs about ... over ..."
  // With --tiles-dir: where the far field's pyramid is kept (far_field_pyramid.h), what identifies
  // the input it is built from, and whether this run read it from there.
  std::string pyramid_file, pyramid_source;
  bool pyramid_reused = false;
  std::vector<int> tiles_by_rank;  // tiles each rank computed in this run (--tiles-dir)
};

// The options' checks that need no input (exit 2 for a tile size below 1, a size that is no size,
// --tiles-dir with an output that is not a .vrt).
void check_tiling_options(const TilingOptions& o, const std::string& output, const std::string& format);

// Whether the run goes by tiles, from the raster's size and the engine's memory model; the halo and
// tile size are filled in by choose_tile_size once the raster's ground frame is known. Throws
// skyview::UsageError where tiles are needed but the run has no finite radius.
TilePlan plan_tiles(const TileRequest& request, const HorizonEngine& engine, int width, int height);
void choose_tile_size(TilePlan& plan, const TileRequest& request, const HorizonEngine& engine, const GroundFrame& frame,
                      int width, int height);

// Mean, range and count of a band's valid cells, summed over tiles.
struct BandStats {
  double sum = 0, lo = INFINITY, hi = -INFINITY;
  std::int64_t n = 0;
  void add(const std::vector<float>& values);
  void add(const BandStats& other);
  // "svf mean 0.812 (0.105 to 1.000)"
  std::string text(const std::string& name) const;
};

// What a run sums over its tiles (kept in a --tiles-dir manifest for the tiles a rerun skips).
struct TileSummary {
  std::int64_t edge_cells = 0;
  BandStats first_band;
  std::string first_band_name;
  void add(const TileSummary& other);
};

// Where a tiled run writes: one raster at `path`, or with `tiles_dir` one GeoTIFF per tile there and
// a VRT mosaic of them at `path`.
struct TiledOutput {
  std::string path, tiles_dir;
  int bands = 1;
  WriteOptions options;  // format, creation options, overwrite, the run's metadata
  std::string identity;  // what besides the job's parameters makes two runs the same (svf's products)
};

// Computes one tile: its window plus halo, the tile's cells inside it, the writer and the place in
// it of the tile's top-left cell. Describes the writer's bands.
using TileWork =
    std::function<TileSummary(const Terrain& part, const Window& inner, BandWriter& out, int col0, int row0)>;

// Runs every tile of a tiled job (skipping, with --tiles-dir, those a manifest of the same run
// records whole) and finishes the output with the job's metadata and the tiling keys; `progress`
// advances by each tile's cells. Returns the sums over all tiles.
TileSummary run_tiles(HorizonJob& job, const TiledOutput& output, ProgressCounter& progress, const TileWork& work);

// The tiling keys of the output's metadata (TILE_SIZE, TILE_HALO_CELLS, TILES, MEMORY_LIMIT,
// TILES_BY_RANK, FAR_FIELD_PYRAMID_REUSED) and the run's measured peak (PEAK_MEMORY_BYTES).
std::map<std::string, std::string> tiling_metadata(const TilePlan& plan);

}  // namespace skyview::cli
