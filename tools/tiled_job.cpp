#include "tiled_job.h"

#include <cmath>

#include "horizon_job.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/tiling/tile_grid.h"

namespace skyview::cli {

void add_tiling_options(CLI::App& app, TilingOptions& o) {
  o.app = &app;
  app.add_option("--tile-size", o.tile_size,
                 "Compute tile by tile, each tile this many cells square, reading its window plus a halo as wide "
                 "as --radius through GDAL (never the whole raster); results are the same as a whole run's. Needs "
                 "a finite --radius");
  app.add_option("--memory-limit", o.memory_limit,
                 "Memory the run may take (8G, 512M; binary units); a run estimated to need more goes tile by tile "
                 "with the largest tiles that fit (default: the memory available when it starts)");
}

void check_tiling_options(const TilingOptions& o) {
  if (o.app && o.app->count("--tile-size") > 0 && o.tile_size < 1)
    throw UsageError("--tile-size must be at least 1 cell, not " + std::to_string(o.tile_size));
  if (!o.memory_limit.empty()) parse_memory_size(o.memory_limit);
}

TilePlan plan_tiles(const TileRequest& request, const HorizonEngine& engine, int width, int height) {
  const TilingOptions& o = request.options;
  TilePlan plan;
  plan.limit = o.memory_limit.empty() ? available_memory_bytes() : parse_memory_size(o.memory_limit);
  plan.whole_estimate = request.memory(engine).bytes(static_cast<std::int64_t>(width) * height);
  if (o.tile_size > 0) {
    plan.tiled = true;
    plan.tile_size = o.tile_size;
    plan.why = "--tile-size " + std::to_string(o.tile_size);
  } else if (plan.limit > 0 && plan.whole_estimate > plan.limit) {
    plan.tiled = true;
    plan.why =
        "the whole run needs about " + memory_text(plan.whole_estimate) + ", over " +
        (o.memory_limit.empty() ? "the " + memory_text(plan.limit) + " available" : "--memory-limit " + o.memory_limit);
  }
  if (plan.tiled && !std::isfinite(engine.radius())) {
    throw UsageError("tiled runs need a finite --radius for now (" + plan.why +
                     "): give --radius in metres; each tile then reads a halo that wide");
  }
  return plan;
}

void choose_tile_size(TilePlan& plan, const TileRequest& request, const HorizonEngine& engine, const GroundFrame& frame,
                      int width, int height) {
  plan.halo = halo_cells(frame, {0, 0, width, height}, engine.radius());
  if (plan.tile_size == 0) {
    plan.tile_size = tile_size_for(request.memory(engine), plan.limit, plan.halo, std::max(width, height));
    if (plan.tile_size == 0) {
      throw Error((request.options.memory_limit.empty() ? "the " + memory_text(plan.limit) + " available"
                                                        : "--memory-limit " + request.options.memory_limit) +
                  " holds no tile with its halo of " + std::to_string(plan.halo) + " cells (--radius " +
                  number_text(engine.radius()) + " m); allow more memory or give a smaller --radius");
    }
  }
  plan.tiles = TileGrid(width, height, plan.tile_size).count();
}

void for_each_tile(const HorizonJob& job, const TileWork& work) {
  const TerrainReader& reader = *job.reader;
  const TileGrid grid(reader.width(), reader.height(), job.tiles.tile_size);
  for (int i = 0; i < grid.count(); ++i) {
    const Window core = grid.core(i);
    const Window read = with_halo(core, job.tiles.halo, reader.width(), reader.height());
    const Terrain part = reader.read(read);
    work(part, inside(core, read), core);
  }
}

std::map<std::string, std::string> tiling_metadata(const TilePlan& plan) {
  std::map<std::string, std::string> m;
  m["PEAK_MEMORY_BYTES"] = std::to_string(peak_memory_bytes());
  if (!plan.tiled) return m;
  m["TILE_SIZE"] = std::to_string(plan.tile_size);
  m["TILE_HALO_CELLS"] = std::to_string(plan.halo);
  m["TILES"] = std::to_string(plan.tiles);
  m["TILING"] = plan.why + "; each tile computed on its window plus the halo, as the whole raster gives it";
  m["MEMORY_LIMIT_BYTES"] = std::to_string(plan.limit);
  return m;
}

}  // namespace skyview::cli
