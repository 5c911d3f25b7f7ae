#include "tiled_job.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "far_field_pyramid.h"
#include "horizon_job.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/core/version.h"
#include "skyview/raster/vrt_mosaic.h"
#include "skyview/tiling/tile_grid.h"
#include "skyview/tiling/tile_manifest.h"
#include "tile_ranks.h"

namespace skyview::cli {

void add_tiling_options(CLI::App& app, TilingOptions& o) {
  o.app = &app;
  app.add_option("--tile-size", o.tile_size,
                 "Compute tile by tile, each tile this many cells square, reading its window plus a halo as wide "
                 "as --radius through GDAL (never the whole raster); results are the same as a whole run's. Without "
                 "--radius a far field beyond a halo chosen by --far-field-error bounds the error (docs/tiling.md)");
  app.add_option("--tiles-dir", o.tiles_dir,
                 "Write one GeoTIFF per tile into this folder (tile_<row>_<col>.tif, created if missing) and a VRT "
                 "mosaic of them at the output (which must end in .vrt), with a manifest (manifest.json) that lets a "
                 "rerun of the same command skip the tiles already finished; a far field's pyramid is kept there "
                 "too (far_field_pyramid.bin), for reruns of the same input");
  app.add_option("--memory-limit", o.memory_limit,
                 "Memory the run may take (8G, 512M; binary units); a run estimated to need more goes tile by tile "
                 "with the largest tiles that fit (default: the memory available when it starts)");
}

void check_tiling_options(const TilingOptions& o, const std::string& output, const std::string& format) {
  if (o.app && o.app->count("--tile-size") > 0 && o.tile_size < 1)
    throw UsageError("--tile-size must be at least 1 cell, not " + std::to_string(o.tile_size));
  if (!o.memory_limit.empty()) parse_memory_size(o.memory_limit);
  if (o.app && o.app->count("--tiles-dir") > 0) {
    if (o.tiles_dir.empty()) throw UsageError("--tiles-dir needs a folder");
    require_extension(output, {".vrt"}, "the output of --tiles-dir (a VRT mosaic of the tiles)");
    if (format != "GTiff") throw UsageError("--tiles-dir writes GeoTIFF tiles: leave out -of " + format);
  }
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
  } else if (!o.tiles_dir.empty()) {
    plan.tiled = true;
    plan.why = "--tiles-dir";
  } else if (plan.limit > 0 && plan.whole_estimate > plan.limit) {
    plan.tiled = true;
    plan.why =
        "the whole run needs about " + memory_text(plan.whole_estimate) + ", over " +
        (o.memory_limit.empty() ? "the " + memory_text(plan.limit) + " available" : "--memory-limit " + o.memory_limit);
  }
  if (plan.tiled && !std::isfinite(engine.radius()) && !request.far_field) {
    throw UsageError("tiled runs need a finite --radius for now (" + plan.why +
                     "): give --radius in metres; each tile then reads a halo that wide");
  }
  return plan;
}

void choose_tile_size(TilePlan& plan, const TileRequest& request, const HorizonEngine& engine, const GroundFrame& frame,
                      int width, int height) {
  plan.halo = halo_cells(frame, {0, 0, width, height}, plan.far_field ? plan.halo_m : engine.radius());
  if (plan.tile_size == 0) {
    plan.tile_size = tile_size_for(request.memory(engine), plan.limit - std::min(plan.limit, plan.reserved), plan.halo,
                                   std::max(width, height));
    if (plan.tile_size == 0) {
      throw Error((request.options.memory_limit.empty() ? "the " + memory_text(plan.limit) + " available"
                                                        : "--memory-limit " + request.options.memory_limit) +
                  " holds no tile with its halo of " + std::to_string(plan.halo) + " cells" +
                  (plan.far_field ? " (" + number_text(plan.halo_m) +
                                        " m, what the far field's bound asks for); allow more memory or give a larger "
                                        "--far-field-error or a --radius"
                                  : " (--radius " + number_text(engine.radius()) +
                                        " m); allow more memory or give a smaller --radius"));
    }
  }
  plan.tiles = TileGrid(width, height, plan.tile_size).count();
}

void BandStats::add(const std::vector<float>& values) {
  for (float v : values) {
    if (std::isnan(v)) continue;
    sum += v;
    lo = std::min(lo, static_cast<double>(v));
    hi = std::max(hi, static_cast<double>(v));
    ++n;
  }
}

void BandStats::add(const BandStats& o) {
  sum += o.sum;
  lo = std::min(lo, o.lo);
  hi = std::max(hi, o.hi);
  n += o.n;
}

std::string BandStats::text(const std::string& name) const {
  if (n == 0) return name + ": no valid cells";
  char text[160];
  std::snprintf(text, sizeof text, "%s mean %.3f (%.3f to %.3f)", name.c_str(), sum / n, lo, hi);
  return text;
}

void TileSummary::add(const TileSummary& o) {
  edge_cells += o.edge_cells;
  first_band.add(o.first_band);
  if (first_band_name.empty()) first_band_name = o.first_band_name;
}

namespace {

nlohmann::json to_json(const TileSummary& t) {
  nlohmann::json j = {
      {"edge_cells", t.edge_cells}, {"band", t.first_band_name}, {"n", t.first_band.n}, {"sum", t.first_band.sum}};
  if (t.first_band.n > 0) j["lo"] = t.first_band.lo, j["hi"] = t.first_band.hi;
  return j;
}

TileSummary summary_from_json(const nlohmann::json& j) {
  TileSummary t;
  t.edge_cells = j.value("edge_cells", std::int64_t{0});
  t.first_band_name = j.value("band", std::string());
  t.first_band.n = j.value("n", std::int64_t{0});
  t.first_band.sum = j.value("sum", 0.0);
  if (t.first_band.n > 0) t.first_band.lo = j.value("lo", 0.0), t.first_band.hi = j.value("hi", 0.0);
  return t;
}

// What makes two runs into one folder the same run: the input as it is on disk, the job's
// parameters (not the command line, which -q or --overwrite change), the tiles, the version.
nlohmann::json run_identity(const HorizonJob& job, const TiledOutput& output, const std::string& input) {
  nlohmann::json params = nlohmann::json::object();
  for (const auto& [k, v] : job.metadata) {
    if (k != "SKYVIEW_COMMAND" && k != "EDGE_CELLS" && k != "EDGE_NOTE") params[k] = v;
  }
  return {{"input", input_identity(input)},
          {"parameters", params},
          {"products", output.identity},
          {"bands", output.bands},
          {"creation_options", output.options.creation_options},
          {"width", job.width()},
          {"height", job.height()},
          {"tile_size", job.tiles.tile_size},
          {"halo", job.tiles.halo},
          {"version", version()}};
}

std::string tile_name(const TileGrid& grid, int index) {
  return "tile_" + std::to_string(grid.tile_row(index)) + "_" + std::to_string(grid.tile_col(index)) + ".tif";
}

}  // namespace

TileSummary run_tiles(HorizonJob& job, const TiledOutput& output, ProgressCounter& progress, const TileWork& work) {
  const TerrainReader& reader = *job.reader;
  const TileGrid grid(reader.width(), reader.height(), job.tiles.tile_size);
  TileSummary total;
  auto late_metadata = [&] {
    record_edge_cells(job, total.edge_cells);
    std::map<std::string, std::string> m = job.metadata;
    for (const auto& [k, v] : tiling_metadata(job.tiles)) m[k] = v;
    return m;
  };
  if (output.tiles_dir.empty()) {
    BandWriter out(output.path, grid.width(), grid.height(), output.bands, reader.georef(), output.options);
    for (int i = 0; i < grid.count(); ++i) {
      const Window core = grid.core(i);
      const Window read = with_halo(core, job.tiles.halo, reader.width(), reader.height());
      total.add(work(reader.read(read), inside(core, read), out, core.col0, core.row0));
    }
    out.set_metadata(late_metadata());
    out.finish();
    return total;
  }
  // One GeoTIFF per tile, each recorded in the manifest as soon as it is in place.
  const std::filesystem::path dir(output.tiles_dir);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error("cannot create the tiles folder '" + output.tiles_dir + "': " + ec.message());
  const std::string manifest_path = (dir / "manifest.json").string();
  const nlohmann::json identity = run_identity(job, output, job.metadata.at("SOURCE"));
  TileManifest manifest(identity);
  try {  // rank 0 alone keeps the manifest; under mpirun a refusal ends every rank
    if (std::optional<TileManifest> old =
            TileRanks::world().rank() == 0 ? TileManifest::load(manifest_path) : std::nullopt) {
      if (old->same_run(identity)) {
        manifest = std::move(*old);
      } else if (!output.options.overwrite) {
        throw Error("the tiles folder '" + output.tiles_dir +
                    "' holds the tiles of another run (another input, options or version; see its manifest.json); "
                    "use --overwrite to replace them");
      }
    }
  } catch (const Error& e) {
    if (!TileRanks::world().parallel()) throw;
    TileRanks::world().abort(job.metadata.at("SKYVIEW_PRODUCT"), e.what());
  }
  if (TileRanks::world().rank() == 0) {  // the far field's pyramid kept beside the tiles, for reruns
    try {
      if (keep_run_pyramid(job, manifest)) manifest.save(manifest_path);  // even where no tile is left
    } catch (const Error& e) {
      if (!TileRanks::world().parallel()) throw;
      TileRanks::world().abort(job.metadata.at("SKYVIEW_PRODUCT"), e.what());
    }
  }
  std::vector<std::string> files;
  for (int i = 0; i < grid.count(); ++i) files.push_back((dir / tile_name(grid, i)).string());
  // A tile computed, written under a temporary name, renamed into place, and its record.
  auto make_tile = [&](int i) {
    const Window core = grid.core(i);
    WriteOptions wo = output.options;
    wo.overwrite = true;  // a tile the manifest does not record whole is made again
    wo.metadata["TILE_ROW"] = std::to_string(grid.tile_row(i));
    wo.metadata["TILE_COL"] = std::to_string(grid.tile_col(i));
    const Window read = with_halo(core, job.tiles.halo, reader.width(), reader.height());
    const Terrain part = reader.read(read);
    const std::string& file = files[static_cast<std::size_t>(i)];
    BandWriter out(file, core.cols, core.rows, output.bands, reader.georef().window(core.col0, core.row0), wo);
    const TileSummary summary = work(part, inside(core, read), out, 0, 0);
    out.finish();
    return TileRecord{tile_name(grid, i), file_checksum(file), to_json(summary)};
  };
  TileRanks& ranks = TileRanks::world();
  const std::string command = job.metadata.at("SKYVIEW_PRODUCT");
  if (ranks.parallel() && ranks.rank() > 0) {  // compute what rank 0 hands out, then stop
    try {
      ranks.work([&](int i) {
        const TileRecord record = make_tile(i);
        return record.checksum + "\n" + record.summary.dump();
      });
    } catch (const std::exception& e) {
      ranks.abort(command, e.what());
    }
    ranks.finish_worker();
  }
  // The tiles still to make: those the manifest does not record, or whose file is missing or changed.
  std::vector<int> todo;
  int skipped = 0;
  for (int i = 0; i < grid.count(); ++i) {
    const std::string name = tile_name(grid, i);
    if (const TileRecord* done = manifest.find(name)) {
      const std::string& file = files[static_cast<std::size_t>(i)];
      std::error_code missing;
      if (std::filesystem::exists(file, missing) && file_checksum(file) == done->checksum) {
        total.add(summary_from_json(done->summary));
        progress.advance(static_cast<std::uint64_t>(grid.core(i).cells()));
        ++skipped;
        continue;
      }
      manifest.forget(name);
    }
    todo.push_back(i);
  }
  job.tiles.tiles_by_rank.assign(static_cast<std::size_t>(ranks.size()), 0);
  // A finished tile into the sums and the manifest; `rank` made it (rank 0's work advanced the
  // progress itself, as a single process's does).
  auto record = [&](int i, int rank, TileRecord tile) {
    total.add(summary_from_json(tile.summary));
    tile.summary["rank"] = rank;
    manifest.record(tile.file, tile);
    manifest.save(manifest_path);
    ++job.tiles.tiles_by_rank[static_cast<std::size_t>(rank)];
    progress.advance(rank > 0 ? static_cast<std::uint64_t>(grid.core(i).cells()) : 0);
  };
  if (ranks.parallel()) {
    try {
      ranks.serve(
          todo,
          [&](int i) {
            const TileRecord tile = make_tile(i);
            return tile.checksum + "\n" + tile.summary.dump();
          },
          [&](int i, int rank, const std::string& message) {
            const std::size_t cut = message.find('\n');
            record(i, rank,
                   {tile_name(grid, i), message.substr(0, cut), nlohmann::json::parse(message.substr(cut + 1))});
          });
    } catch (const std::exception& e) {
      ranks.abort(command, e.what());
    }
  } else {
    for (int i : todo) record(i, 0, make_tile(i));
  }
  job.tiles.skipped = skipped;
  write_vrt_mosaic(output.path, files, late_metadata(), output.options.overwrite);
  return total;
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
  if (plan.skipped > 0) m["TILES_REUSED"] = std::to_string(plan.skipped);
  if (plan.tiles_by_rank.size() > 1) {  // under mpirun: "rank 0: 9, rank 1: 7"
    std::string by_rank;
    for (std::size_t r = 0; r < plan.tiles_by_rank.size(); ++r)
      by_rank += (r > 0 ? ", rank " : "rank ") + std::to_string(r) + ": " + std::to_string(plan.tiles_by_rank[r]);
    m["TILES_BY_RANK"] = by_rank;
  }
  if (plan.pyramid_reused) m["FAR_FIELD_PYRAMID_REUSED"] = plan.pyramid_file;
  return m;
}

}  // namespace skyview::cli
