// skyview horizon: horizon elevation angle per direction, one band per azimuth.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "far_field_job.h"
#include "horizon_job.h"
#include "preview_options.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/sky_view/horizon_bands.h"

namespace skyview::cli {
namespace {

// Horizons of `window` of `terrain` in degrees, written into `out` with the window's top-left cell
// at (out_col0, out_row0): the whole raster at (0, 0), or a tile's cells inside its window plus
// halo at the tile's place. Band `drawn` is also copied into `drawn_values` (the whole output's
// size) when given, for the preview. Returns the cells whose search leaves the raster.
std::int64_t write_horizons(const HorizonJob& job, const Terrain& terrain, const Window& window, int out_col0,
                            int out_row0, BandWriter& out, ProgressCounter& progress, int drawn = -1,
                            Grid<float>* drawn_values = nullptr) {
  const int n = job.engine->params().directions;
  std::int64_t edge_cells = 0;
  // A tiled run without --radius searches without limit: the far field beyond its halo.
  const std::vector<unsigned char> blank = horizon_blank_cells(
      job, terrain, window, edge_cells, job.far_field ? std::optional<double>(INFINITY) : std::nullopt);  // nodata
  std::vector<float> degrees, raised;
  // Rows [row0, row0 + rows) of the window for direction k from its plane of radians over those rows.
  auto write_rows = [&](int k, int row0, int rows, const float* radians) {
    const std::size_t first = static_cast<std::size_t>(row0) * window.cols,
                      count = static_cast<std::size_t>(rows) * window.cols;
    degrees.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      degrees[i] =
          blank[first + i] ? std::numeric_limits<float>::quiet_NaN() : static_cast<float>(radians[i] * 180.0 / M_PI);
    }
    out.write_window(k, out_col0, out_row0 + row0, window.cols, rows, degrees.data());
    if (k != drawn || !drawn_values) return;
    for (int r = 0; r < rows; ++r)
      std::copy_n(degrees.data() + static_cast<std::size_t>(r) * window.cols, window.cols,
                  &(*drawn_values)(out_col0, out_row0 + row0 + r));
  };
  if (job.engine->streams_directions()) {
    HorizonField rest;
    job.engine->compute_directions(terrain, window, rest, progress,
                                   [&](int first, int count, const float* upper, const float*) {
                                     for (int j = 0; j < count; ++j) {
                                       const float* plane = upper + window.cells() * j;
                                       if (job.far_field) {
                                         raised.assign(plane, plane + window.cells());
                                         job.far_field->raise(terrain, window, rest, first + j, raised.data());
                                         plane = raised.data();
                                       }
                                       write_rows(first + j, 0, window.rows, plane);
                                     }
                                   });
  } else {
    compute_by_row_blocks(*job.engine, terrain, window, progress, kHorizonBlockBytes, out.block_rows(),
                          [&](const Window& block, HorizonField& field) {
                            for (int k = 0; k < n; ++k) {
                              if (job.far_field) job.far_field->raise(terrain, block, field, k, field.upper_plane(k));
                              write_rows(k, block.row0 - window.row0, block.rows, field.upper_plane(k));
                            }
                          });
  }
  return edge_cells;
}

Runner setup(CLI::App& app) {
  auto o = std::make_shared<HorizonJobOptions>();
  auto preview = std::make_shared<PreviewOptions>();
  auto tiling = std::make_shared<TileRequest>();
  add_horizon_job_options(app, *o);
  add_preview_options(app, *preview,
                      "Also write a PNG of the first direction's band, or --preview-band's (horizon_azimuth_90)");
  add_tiling_options(app, tiling->options);
  add_far_field_option(app, *tiling, "--max-error, else ");
  tiling->memory = [](const HorizonEngine& engine) { return horizon_memory(engine); };
  app.footer(
      "One band per direction, in degrees above the horizontal; band k is centred on azimuth 360*k/N (plus "
      "SECTOR_ROTATION_DEG with --azimuth-origin grid; with --azimuths grid-lines on the grid's lines); each band's "
      "AZIMUTH_DEG says where and SECTOR_WIDTH_DEG how wide an angle it stands for.");
  return [o, preview, tiling, &app] {
    const RunSummary summary("horizon");
    refuse_unused(app, "--rays", false, "skyview svf (its Monte-Carlo svf bands)");
    ThreadLimit limit(o->out.threads);
    HorizonJobOptions opts = *o;
    opts.params.rays = 0;  // the ray cast's Monte-Carlo svf is not a horizon band
    HorizonJob job = prepare_horizon_job(opts, "horizon", {preview->path}, tiling.get());
    check_far_field_option(app, job);
    if (job.tiles.tiled && !preview->path.empty())
      throw UsageError("--preview needs the whole raster, and the run goes by tiles (" + job.tiles.why + ")");
    const int w = job.width(), h = job.height(), n = job.engine->params().directions;
    WriteOptions wo;
    wo.format = o->out.format;
    wo.creation_options = o->out.creation_options;
    wo.overwrite = o->out.overwrite;
    wo.metadata = job.metadata;
    if (job.engine->name() == "sampled") {
      wo.metadata["AZIMUTH_NOTE"] = "sampled rotates each cell's direction set randomly within +-half a sector";
    }
    // Bands are written as the method finds them: the sweep's directions one at a time (only those
    // in progress are held), the other methods' in blocks of whole rows, a multiple of the
    // output's tile height so that each tile is compressed once, and tiles no taller than such a
    // block. Memory does not grow with the number of directions. (Tiled runs write each tile's
    // window into the format's default blocks.)
    if (!job.engine->streams_directions() && !job.tiles.tiled)
      wo.rows_at_once = rows_in_budget(*job.engine, w, kHorizonBlockBytes);
    const std::vector<DirectionBand> directions = direction_bands(job);
    std::vector<std::string> names;
    for (const DirectionBand& d : directions) names.push_back("horizon_azimuth_" + d.azimuth_deg);
    const int drawn = static_cast<int>(check_preview_options(app, *preview, names));
    Grid<float> drawn_values;
    if (!preview->path.empty()) drawn_values = Grid<float>(w, h);
    auto describe = [&](BandWriter& out) {
      for (int k = 0; k < n; ++k) {
        const std::size_t i = static_cast<std::size_t>(k);
        out.describe(k, {names[i],
                         "degree",
                         nullptr,
                         {{"AZIMUTH_DEG", directions[i].azimuth_deg},
                          {"SECTOR_WIDTH_DEG", number_text(directions[i].width_deg)}}});
      }
    };
    std::int64_t edge_cells = 0;
    if (job.tiles.tiled) {
      TiledOutput output;
      output.path = o->output;
      output.tiles_dir = tiling->options.tiles_dir;
      output.bands = n;
      output.options = wo;
      with_progress(job, [&](ProgressCounter& progress) {
        edge_cells = run_tiles(job, output, progress,
                               [&](const Terrain& part, const Window& inner, BandWriter& out, int col0, int row0) {
                                 describe(out);
                                 TileSummary tile;
                                 tile.edge_cells = write_horizons(job, part, inner, col0, row0, out, progress);
                                 return tile;
                               })
                         .edge_cells;
      });
    } else {
      BandWriter out(o->output, w, h, n, job.georef(), wo);
      describe(out);
      with_progress(job, [&](ProgressCounter& progress) {
        edge_cells = write_horizons(job, job.terrain, Window::whole(job.terrain), 0, 0, out, progress, drawn,
                                    preview->path.empty() ? nullptr : &drawn_values);
      });
      record_edge_cells(job, edge_cells);
      std::map<std::string, std::string> late = tiling_metadata(job.tiles);
      for (const char* key : {"EDGE_CELLS", "EDGE_NOTE"}) {
        if (job.metadata.count(key)) late[key] = job.metadata.at(key);
      }
      out.set_metadata(late);
      out.finish();
    }
    write_preview(*preview, drawn_values,
                  {names[static_cast<std::size_t>(drawn)], "degree", o->output, job.georef(), {}, {}},
                  o->out.overwrite);
    summary.print(std::to_string(w) + "x" + std::to_string(h) + " cells, " + std::to_string(n) +
                      " direction bands by " + std::string(job.engine->name()) + "; " + std::to_string(edge_cells) +
                      " cells whose search leaves the raster" +
                      (job.tiles.tiled ? "; " + std::to_string(job.tiles.tiles) + " tiles of " +
                                             std::to_string(job.tiles.tile_size) + " cells, halo " +
                                             std::to_string(job.tiles.halo) + far_field_summary(job)
                                       : ""),
                  o->out.quiet);
    return 0;
  };
}

const Registration reg("horizon", "Horizon angle per direction (one band per azimuth) from a DEM/DSM", setup);

}  // namespace
}  // namespace skyview::cli
