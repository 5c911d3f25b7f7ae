// skyview svf: sky-view factor, sky visibility and openness of every cell.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/preview/raster_preview.h"
#include "skyview/sky_view/svf_run.h"

#include "horizon_job.h"

namespace skyview::cli {
namespace {

// "svf mean 0.812 (0.105 to 1.000)" over the band's valid cells.
std::string band_summary(const SvfBand& band) {
  double sum = 0, lo = INFINITY, hi = -INFINITY;
  std::size_t n = 0;
  for (float v : band.values.values()) {
    if (std::isnan(v)) continue;
    sum += v;
    lo = std::min(lo, static_cast<double>(v));
    hi = std::max(hi, static_cast<double>(v));
    ++n;
  }
  if (n == 0) return band.name + ": no valid cells";
  char text[160];
  std::snprintf(text, sizeof text, "%s mean %.3f (%.3f to %.3f)", band.name.c_str(), sum / n, lo, hi);
  return text;
}

Runner setup(CLI::App& app) {
  auto o = std::make_shared<HorizonJobOptions>();
  auto preview = std::make_shared<std::string>();
  auto check_cells = std::make_shared<int>(-1);
  auto products = std::make_shared<std::string>(default_svf_products());
  o->azimuth_origin = default_svf_horizon_request().azimuth_origin;
  add_horizon_job_options(app, *o);
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
  app.add_option("--check-cells", *check_cells,
                 "Measure the svf's error on this many random cells against exact horizons and record it in the "
                 "metadata (SVF_CHECK_*); with --max-error (default 1000 cells) a run whose measured p99 exceeds the "
                 "request runs again with a finer choice; 0: no check")
      ->check(CLI::Range(0, 10000000));
  app.add_option("--preview", *preview, "Also write a PNG of the first band written (nodata transparent)");
  app.footer(
      "Bands (--products): svf (cosine-weighted, horizontal surface), svf_surface (the cell's tilted surface), "
      "sky_visibility (solid-angle fraction), openness_positive, openness_negative (degrees); raycast with --rays "
      "adds svf_montecarlo and svf_montecarlo_stderr.");
  return [o, preview, products, check_cells] {
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
    HorizonJob job = prepare_horizon_job(opts, "svf", {*preview});
    if (!preview->empty()) require_extension(*preview, {".png"}, "--preview");
    const bool monte_carlo = job.engine->name() == "raycast" && job.engine->params().rays > 0;
    check_output_format(o->output, o->out.format,
                        static_cast<int>(parse_svf_products(*products).size()) + (monte_carlo ? 2 : 0),
                        o->out.creation_options);
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
    const int w = job.terrain.width(), h = job.terrain.height();
    std::vector<OutputBand> bands;
    for (const SvfBand& b : result.bands) bands.push_back({b.name, b.unit, b.values.data(), b.metadata});
    write_bands(o->output, w, h, job.terrain.georef, bands, wo);
    if (!preview->empty()) {
      PreviewSpec spec;
      spec.band = result.bands.front().name;
      spec.unit = result.bands.front().unit;
      spec.title = spec.band + " - " + o->output;
      spec.georef = job.terrain.georef;
      if (spec.unit == "1") spec.range = std::make_pair(0.0, 1.0);
      write_raster_preview(*preview, result.bands.front().values, spec, o->out.overwrite);
    }
    summary.print(std::to_string(w) + "x" + std::to_string(h) + " cells, " + std::to_string(bands.size()) +
                      " bands by " + std::string(job.engine->name()) + " with " +
                      std::to_string(job.engine->params().directions) + " directions; " +
                      band_summary(result.bands.front()),
                  o->out.quiet);
    return 0;
  };
}

const Registration reg("svf", "Sky-view factor, sky visibility and openness GeoTIFF from a DEM/DSM", setup);

}  // namespace
}  // namespace skyview::cli
