// skyview svf: sky-view factor, sky visibility and openness of every cell.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/sky_view/svf_run.h"
#include "skyview/tiling/memory_budget.h"

#include "far_field_job.h"
#include "horizon_job.h"
#include "preview_options.h"

namespace skyview::cli {
namespace {

// The run tile by tile: each tile's window plus halo through the same run_svf as a whole run, its
// own cells written into the output's window.
int run_tiled_svf(const HorizonJobOptions& o, const TilingOptions& tiling, const SvfRequest& request, HorizonJob& job,
                  int n_bands, const RunSummary& summary) {
  TiledOutput output;
  output.path = o.output;
  output.tiles_dir = tiling.tiles_dir;
  output.bands = n_bands;
  output.identity = request.products;
  output.options.format = o.out.format;
  output.options.creation_options = o.out.creation_options;
  output.options.overwrite = o.out.overwrite;
  output.options.metadata = job.metadata;
  TileSummary total;
  with_progress(job, [&](ProgressCounter& progress) {
    total = run_tiles(
        job, output, progress, [&](const Terrain& part, const Window& inner, BandWriter& out, int col0, int row0) {
          const SvfResult result = run_svf(
              part, request, job, [&](const std::function<void(ProgressCounter&)>& work) { work(progress); }, inner);
          if (static_cast<int>(result.bands.size()) != n_bands)
            throw Error("a tile gave " + std::to_string(result.bands.size()) + " bands, not " +
                        std::to_string(n_bands) + " (internal error)");
          for (int b = 0; b < n_bands; ++b) {
            const SvfBand& band = result.bands[static_cast<std::size_t>(b)];
            out.write_window(b, col0, row0, inner.cols, inner.rows, band.values.data());
            out.describe(b, {band.name, band.unit, nullptr, band.metadata});
          }
          TileSummary tile;
          tile.first_band_name = result.bands.front().name;
          tile.first_band.add(result.bands.front().values.values());
          tile.edge_cells = std::stoll(result.metadata.at("EDGE_CELLS"));
          return tile;
        });
  });
  summary.print(std::to_string(job.width()) + "x" + std::to_string(job.height()) + " cells, " +
                    std::to_string(n_bands) + " bands by " + std::string(job.engine->name()) + " with " +
                    std::to_string(job.engine->params().directions) + " directions in " +
                    std::to_string(job.tiles.tiles) + " tiles of " + std::to_string(job.tiles.tile_size) +
                    " cells (halo " + std::to_string(job.tiles.halo) + " cells" +
                    (job.tiles.skipped > 0 ? ", " + std::to_string(job.tiles.skipped) + " already finished" : "") +
                    far_field_summary(job) + "); " + total.first_band.text(total.first_band_name),
                o.out.quiet);
  return 0;
}

Runner setup(CLI::App& app) {
  auto o = std::make_shared<HorizonJobOptions>();
  auto preview = std::make_shared<PreviewOptions>();
  auto check_cells = std::make_shared<int>(-1);
  auto products = std::make_shared<std::string>(default_svf_products());
  auto tiling = std::make_shared<TileRequest>();
  o->azimuth_origin = default_svf_horizon_request().azimuth_origin;
  add_horizon_job_options(app, *o);
  add_tiling_options(app, tiling->options);
  app.add_option("--products", *products,
                 "Bands to write, in this order; without openness_negative the lowest angles are not computed "
                 "(about half the sweep's time)")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](std::string& list) {
            try {
              parse_svf_products(list);
              return std::string();
            } catch (const Error& e) {
              return std::string(e.what());
            }
          },
          "LIST"));
  add_far_field_option(app, *tiling, "--max-error, else ");
  app.add_option("--check-cells", *check_cells,
                 "Measure the svf's error on this many random cells against exact horizons and record it in the "
                 "metadata (SVF_CHECK_*); with --max-error (default 1000 cells) a run whose measured p99 exceeds the "
                 "request runs again with a finer choice; 0: no check")
      ->check(CLI::Range(0, 10000000));
  add_preview_options(app, *preview,
                      "Also write a PNG of the first band written, or --preview-band's (docs/previews.md)");
  app.footer(
      "Bands (--products): svf (cosine-weighted, horizontal surface), svf_surface (the cell's tilted surface), "
      "sky_visibility (solid-angle fraction), openness_positive, openness_negative (degrees); raycast with --rays "
      "adds svf_montecarlo and svf_montecarlo_stderr.");
  return [o, preview, products, check_cells, tiling, &app] {
    const RunSummary summary("svf");
    SvfRequest request;
    request.products = *products;
    request.check_cells = *check_cells;
    ThreadLimit limit(o->out.threads);
    HorizonJobOptions opts = *o;
    // Negative openness is the only product that needs the lowest angles, a second walk.
    for (const SvfProductInfo* c : parse_svf_products(*products))
      if (c->product == Product::openness_negative) opts.params.lower = true;
    request.horizon = horizon_request(opts);
    check_svf_request(request);
    ProductSet keep = ProductSet::none();
    for (const SvfProductInfo* c : parse_svf_products(*products)) keep.add(c->product);
    const int n_products = static_cast<int>(parse_svf_products(*products).size());
    tiling->memory = [keep, n_products](const HorizonEngine& engine) {
      return svf_memory(engine, keep, n_products + (engine.name() == "raycast" && engine.params().rays > 0 ? 2 : 0));
    };
    HorizonJob job = prepare_horizon_job(opts, "svf", {preview->path}, tiling.get());
    const bool monte_carlo = job.engine->name() == "raycast" && job.engine->params().rays > 0;
    std::vector<std::string> names;
    for (const SvfProductInfo* c : parse_svf_products(*products)) names.push_back(c->name);
    if (monte_carlo) names.insert(names.end(), {"svf_montecarlo", "svf_montecarlo_stderr"});
    const std::size_t drawn = check_preview_options(app, *preview, names);
    const int n_bands = n_products + (monte_carlo ? 2 : 0);
    if (tiling->options.tiles_dir.empty())
      check_output_format(o->output, o->out.format, n_bands, o->out.creation_options);
    check_far_field_option(app, job);
    if (job.tiles.tiled) {
      // What needs the whole raster at once: the check's random cells (and --max-error's reruns on
      // them), the preview picture.
      const std::string tiled = "the run goes by tiles (" + job.tiles.why + ")";
      // --max-error chooses the method by its calibration and, at unlimited radius, the halo by the
      // far field's bound; the check of random cells needs the whole raster.
      if (o->max_error >= 0 && !job.far_field)
        throw UsageError("--max-error is not available when " + tiled + " with a finite radius yet");
      if (*check_cells > 0) throw UsageError("--check-cells is not available when " + tiled + " yet");
      request.check_cells = 0;
      request.far_field = job.far_field;
      if (!preview->path.empty()) throw UsageError("--preview needs the whole raster, and " + tiled);
      return run_tiled_svf(*o, tiling->options, request, job, n_bands, summary);
    }
    const SvfResult result = run_svf(job.terrain, request, job, [&](const std::function<void(ProgressCounter&)>& work) {
      with_progress(job, work);
    });
    if (!o->out.quiet) {
      for (const std::string& line : result.messages) std::fprintf(stderr, "%s\n", line.c_str());
    }
    for (const std::string& line : result.warnings) std::fprintf(stderr, "Warning: %s\n", line.c_str());
    WriteOptions wo;
    wo.format = o->out.format;
    wo.creation_options = o->out.creation_options;
    wo.overwrite = o->out.overwrite;
    wo.metadata = job.metadata;
    for (const auto& [k, v] : result.metadata) wo.metadata[k] = v;
    for (const auto& [k, v] : tiling_metadata(job.tiles)) wo.metadata[k] = v;
    const int w = job.terrain.width(), h = job.terrain.height();
    std::vector<OutputBand> bands;
    for (const SvfBand& b : result.bands) bands.push_back({b.name, b.unit, b.values.data(), b.metadata});
    write_bands(o->output, w, h, job.terrain.georef, bands, wo);
    if (!preview->path.empty()) {
      const auto it = std::find_if(result.bands.begin(), result.bands.end(),
                                   [&](const SvfBand& b) { return b.name == names[drawn]; });
      if (it == result.bands.end())
        throw Error("the preview's band " + names[drawn] + " was not made (internal error)");
      write_preview(*preview, it->values, {it->name, it->unit, o->output, job.terrain.georef, {}, {}},
                    o->out.overwrite);
    }
    BandStats stats;
    stats.add(result.bands.front().values.values());
    summary.print(std::to_string(w) + "x" + std::to_string(h) + " cells, " + std::to_string(bands.size()) +
                      " bands by " + std::string(job.engine->name()) + " with " +
                      std::to_string(job.engine->params().directions) + " directions; " +
                      stats.text(result.bands.front().name),
                  o->out.quiet);
    return 0;
  };
}

const Registration reg("svf", "Sky-view factor, sky visibility and openness GeoTIFF from a DEM/DSM", setup);

}  // namespace
}  // namespace skyview::cli
