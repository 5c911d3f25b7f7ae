// skyview exposure: solar exposure of every cell of a DSM over a period (docs/commands/exposure.md).
#include <cmath>
#include <cstdio>
#include <optional>
#include <set>

#include "far_field_job.h"
#include "horizon_job.h"
#include "preview_options.h"
#include "sky_job.h"
#include "skyview/core/error.h"
#include "skyview/exposure/exposure.h"
#include "skyview/exposure/exposure_job.h"
#include "skyview/sky/skymap_file.h"
#include "skyview/tiling/memory_budget.h"

namespace skyview::cli {
namespace {

struct Options {
  HorizonJobOptions job;
  SkyRequest sky;
  std::string method = "fast", skymap, albedo, reads = "area";
  PreviewOptions preview;
  int map_size = 512;
  bool allow_site_mismatch = false;
  TileRequest tiling;
  const CLI::App* app = nullptr;
};

const std::vector<ExposureBandInfo>& kBands = exposure_band_info();
const int kBandCount = static_cast<int>(kBands.size());

// The run tile by tile (docs/tiling.md): each tile's window plus halo through compute_exposure with
// the tile's own cells as its window, those cells written at the tile's place. The sky is the whole
// run's, made once; an albedo raster is read a tile's window at a time. Returns the sums over the
// tiles (the total band's); adds the cells without albedo to `albedo_nodata_cells`.
TileSummary run_tiled_exposure(HorizonJob& job, const Options& o, const ExposureSky& sky,
                               const ExposureRequest& request, const std::string& albedo_raster,
                               std::int64_t& albedo_nodata_cells) {
  TiledOutput output;
  output.path = o.job.output;
  output.tiles_dir = o.tiling.options.tiles_dir;
  output.bands = kBandCount;
  output.identity = "exposure";
  output.options.format = o.job.out.format;
  output.options.creation_options = o.job.out.creation_options;
  output.options.overwrite = o.job.out.overwrite;
  output.options.metadata = job.metadata;
  TileSummary total;
  ThreadLimit limit(o.job.out.threads);
  with_progress(job, [&](ProgressCounter& progress) {
    total = run_tiles(
        job, output, progress, [&](const Terrain& part, const Window& inner, BandWriter& out, int col0, int row0) {
          ExposureRequest tile_request = request;
          if (!albedo_raster.empty()) {
            const Window cells{part.origin_col + inner.col0, part.origin_row + inner.row0, inner.cols, inner.rows};
            tile_request.albedo_grid =
                checked_albedo(read_band(albedo_raster, 1, cells).values, "--albedo '" + albedo_raster + "'");
          }
          const ExposureBands bands = compute_exposure(*job.engine, part, inner, sky, tile_request, progress);
          for (int b = 0; b < kBandCount; ++b) {
            const ExposureBandInfo& info = kBands[b];
            out.write_window(b, col0, row0, inner.cols, inner.rows, (bands.*info.grid).data());
            out.describe(b, {info.name, info.unit, nullptr, {{"DEFINITION", info.definition}}});
          }
          albedo_nodata_cells += bands.albedo_nodata_cells;
          TileSummary tile;
          tile.first_band_name = kBands[0].name;
          tile.first_band.add(bands.total.values());
          tile.edge_cells = bands.edge_cells;
          return tile;
        });
  });
  return total;
}

// The options typed that the exposure job checks, by their long names.
std::set<std::string> given_options(const CLI::App& app) {
  std::set<std::string> given;
  for (const std::string& name : sky_option_names())
    if (app.count(name) > 0) given.insert(name);
  for (const char* name : {"--max-error", "--reads", "--map-size", "--allow-site-mismatch"})
    if (app.count(name) > 0) given.insert(name);
  return given;
}

int run(Options& o) {
  const RunSummary summary("exposure");
  ExposureJobRequest er;
  er.method = o.method;
  er.reads = o.reads;
  er.skymap = o.skymap;
  er.sky = o.sky;
  er.map_size = o.map_size;
  er.allow_site_mismatch = o.allow_site_mismatch;
  er.given = given_options(*o.app);
  check_exposure_job(er);
  er.albedo = parse_exposure_albedo(o.albedo);
  const ExposureAlbedo& albedo = er.albedo;
  std::vector<std::string> band_names;
  for (const ExposureBandInfo& b : kBands) band_names.push_back(b.name);
  const std::size_t drawn = check_preview_options(*o.app, o.preview, band_names);
  check_outputs_apart({o.job.output, o.preview.path}, {o.job.input, o.skymap, o.sky.epw, albedo.raster});

  // The map's cells for the memory model: a map file's are not known before it is read (1024^2
  // stands for them, twice the default's side).
  const bool from_file = er.from_map();
  const std::int64_t map_cells = from_file ? std::int64_t{1024} * 1024 : std::int64_t{o.map_size} * o.map_size;
  o.tiling.memory = [map_cells](const HorizonEngine& engine) { return exposure_memory(engine, map_cells); };
  HorizonJob job = prepare_horizon_job(o.job, "exposure", {o.preview.path}, &o.tiling);
  if (o.tiling.options.tiles_dir.empty())
    check_output_format(o.job.output, o.job.out.format, kBandCount, o.job.out.creation_options);
  check_far_field_option(*o.app, job);
  if (job.tiles.tiled && !o.preview.path.empty())
    throw UsageError("--preview needs the whole raster, and the run goes by tiles (" + job.tiles.why + ")");
  // A tiled run holds only a window about the raster's centre (HorizonJob::terrain).
  const Terrain& t = job.terrain;
  const int width = job.width(), height = job.height();
  auto& meta = job.metadata;

  ExposureJob exposure;
  {
    ThreadLimit limit(o.job.out.threads);
    exposure = prepare_exposure_job(er, {t, width, height, job.georef(), "'" + o.job.input + "'", job.tiles.tiled},
                                    print_warnings);
  }
  ExposureRequest& request = exposure.request;
  request.edge = job.edge;
  request.far_field = job.far_field;
  const ExposureSky& sky = exposure.sky;
  const double global_horizontal = exposure.global_horizontal;
  for (const auto& [key, value] : exposure.metadata) meta[key] = value;

  // The summary line, whole or tiled: the mean of the total band's valid cells.
  auto print_summary = [&](double sum, std::int64_t valid, const std::string& tiles) {
    char what[256];
    std::snprintf(what, sizeof what,
                  "%dx%d cells by %s with %d directions%s; unobstructed global horizontal %.1f kWh/m2, mean total "
                  "%.1f kWh/m2",
                  width, height, o.method.c_str(), job.engine->params().directions, tiles.c_str(),
                  global_horizontal / 1000, valid ? sum / valid : 0.0);
    summary.print(what, o.job.out.quiet);
  };
  auto warn_albedo_nodata = [&](std::int64_t cells) {
    if (cells > 0) {
      std::fprintf(stderr, "Warning: %lld cells have no albedo in '%s': their reflected and total bands are nodata\n",
                   static_cast<long long>(cells), albedo.raster.c_str());
    }
  };

  if (job.tiles.tiled) {
    std::int64_t albedo_nodata_cells = 0;
    const TileSummary total = run_tiled_exposure(job, o, sky, request, exposure.albedo_raster, albedo_nodata_cells);
    warn_albedo_nodata(albedo_nodata_cells);
    print_summary(total.first_band.sum, total.first_band.n,
                  " in " + std::to_string(job.tiles.tiles) + " tiles of " + std::to_string(job.tiles.tile_size) +
                      " cells (halo " + std::to_string(job.tiles.halo) +
                      (job.tiles.skipped > 0 ? ", " + std::to_string(job.tiles.skipped) + " already finished" : "") +
                      far_field_summary(job) + ")");
    return 0;
  }

  ExposureBands bands;
  {
    ThreadLimit limit(o.job.out.threads);
    with_progress(job, [&](ProgressCounter& progress) {
      bands = compute_exposure(*job.engine, t, Window::whole(t), sky, request, progress);
    });
  }
  record_edge_cells(job, bands.edge_cells);
  warn_albedo_nodata(bands.albedo_nodata_cells);

  WriteOptions wo;
  wo.format = o.job.out.format;
  wo.creation_options = o.job.out.creation_options;
  wo.overwrite = o.job.out.overwrite;
  wo.metadata = meta;
  for (const auto& [k, v] : tiling_metadata(job.tiles)) wo.metadata[k] = v;
  std::vector<OutputBand> out;
  for (const ExposureBandInfo& b : kBands)
    out.push_back({b.name, b.unit, (bands.*b.grid).data(), {{"DEFINITION", b.definition}}});
  write_bands(o.job.output, width, height, t.georef, out, wo);
  {
    const ExposureBandInfo& b = kBands[drawn];
    write_preview(o.preview, bands.*b.grid, {b.name, b.unit, o.job.output, t.georef, {}, {}}, o.job.out.overwrite);
  }
  double sum = 0.0;
  std::int64_t valid = 0;
  for (float v : bands.total.values()) {
    if (!std::isnan(v)) sum += v, ++valid;
  }
  print_summary(sum, valid, "");
  return 0;
}

Runner setup(CLI::App& app) {
  auto o = std::make_shared<Options>();
  o->app = &app;
  o->job.method_option = "--horizon-method";
  o->job.azimuth_origin = "grid";  // exposure sums over azimuth
  add_horizon_job_options(app, o->job);
  add_tiling_options(app, o->tiling.options);
  add_far_field_option(app, o->tiling, "");
  app.add_option("--method", o->method,
                 "fast: the exposure map sampled per horizon direction (Section 6 of the paper); exact: the beam of "
                 "every time step against the horizon at the sun's azimuth and the sky at the map's full resolution")
      ->capture_default_str();
  app.add_option("--skymap", o->skymap,
                 "A map written by skyview skymap (its sky, site and period), instead of the "
                 "sky options");
  add_sky_options(app, o->sky, "default: the raster's centre; with --epw and no CRS: the file's");
  app.add_option("--map-size", o->map_size, "Width and height of the exposure map made in memory, cells")
      ->capture_default_str();
  app.add_option("--albedo", o->albedo,
                 "Ground albedo for the reflected light (and Hosek-Wilkie's sky): a number 0-1 or a raster on the "
                 "DSM's grid; default: the EPW's albedo field where it has one, else 0.2");
  app.add_flag("--allow-site-mismatch", o->allow_site_mismatch,
               "Accept a sky made for a site more than 1 degree from the raster's centre");
  app.add_option("--reads", o->reads,
                 "fast: how samples read the map: area (exact rectangles, summed-area table) or mipmap (the paper's "
                 "trilinear reads)")
      ->capture_default_str();
  add_preview_options(app, o->preview, "Also write a PNG of the total band, or --preview-band's");
  app.footer(
      "Bands: total, direct, diffuse, reflected (kWh/m2 over the period on each cell's tilted surface), "
      "horizontal_total (kWh/m2 on a horizontal surface at the cell), svf. See docs/commands/exposure.md.");
  return [o] { return run(*o); };
}

const Registration reg("exposure", "Solar exposure (direct, diffuse, reflected) of every DSM cell over a period",
                       setup);

}  // namespace
}  // namespace skyview::cli
