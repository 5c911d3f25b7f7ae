#pragma once
// Runs of `skyview svf` and `skyview horizon` tile by tile (docs/tiling.md): with --tile-size, or
// when the whole run would take more memory than --memory-limit. Each tile's window plus a halo as
// wide as the search radius is read through GDAL (never the whole raster), computed by the same job
// code as a whole run, and only the tile's own cells are written.
#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include <CLI/CLI.hpp>

#include "skyview/raster/terrain.h"
#include "skyview/tiling/memory_budget.h"

namespace skyview::cli {

struct HorizonJob;

struct TilingOptions {
  int tile_size = 0;         // cells; 0: only where memory asks for tiles
  std::string memory_limit;  // "8G"; empty: the memory available now
  const CLI::App* app = nullptr;
};
void add_tiling_options(CLI::App& app, TilingOptions& o);

// What a command tells the job about tiling: its options and the memory its run takes.
struct TileRequest {
  TilingOptions options;
  std::function<MemoryModel(const HorizonEngine&)> memory;
};

// How a run goes: whole, or by tiles of `tile_size` cells read with `halo` cells around them.
struct TilePlan {
  bool tiled = false;
  int tile_size = 0, halo = 0, tiles = 0;
  std::uint64_t limit = 0;           // bytes (--memory-limit, or what was available)
  std::uint64_t whole_estimate = 0;  // bytes the whole run would take by the memory model
  std::string why;                   // "--tile-size 64", "the whole run needs about ... over ..."
};

// The options' checks that need no input (exit 2 for a tile size below 1, a size that is no size).
void check_tiling_options(const TilingOptions& o);

// Whether the run goes by tiles, from the raster's size and the engine's memory model; the halo and
// tile size are filled in by choose_tile_size once the raster's ground frame is known. Throws
// skyview::UsageError where tiles are needed but the run has no finite radius.
TilePlan plan_tiles(const TileRequest& request, const HorizonEngine& engine, int width, int height);
void choose_tile_size(TilePlan& plan, const TileRequest& request, const HorizonEngine& engine, const GroundFrame& frame,
                      int width, int height);

// Calls `tile` for each tile of a tiled job in order: the tile's window plus halo read from the
// input, the tile's cells inside it, and the same cells in the raster.
using TileWork = std::function<void(const Terrain& part, const Window& inner, const Window& core)>;
void for_each_tile(const HorizonJob& job, const TileWork& tile);

// The tiling keys of the output's metadata (TILE_SIZE, TILE_HALO_CELLS, TILES, MEMORY_LIMIT) and
// the run's measured peak (PEAK_MEMORY_BYTES).
std::map<std::string, std::string> tiling_metadata(const TilePlan& plan);

}  // namespace skyview::cli
