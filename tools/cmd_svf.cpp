// skyview svf: sky-view factor, sky visibility and openness of every cell.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/sky_view/svf_run.h"

#include "horizon_job.h"
#include "preview_options.h"

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
  auto preview = std::make_shared<PreviewOptions>();
  auto check_cells = std::make_shared<int>(-1);
  auto products = std::make_shared<std::string>(default_svf_products());
  o->azimuth_origin = "grid";  // every band sums over azimuth
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
  add_preview_options(app, *preview,
                      "Also write a PNG of the first band written, or --preview-band's (docs/previews.md)");
  app.footer(
      "Bands (--products): svf (cosine-weighted, horizontal surface), svf_surface (the cell's tilted surface), "
      "sky_visibility (solid-angle fraction), openness_positive, openness_negative (degrees); raycast with --rays "
      "adds svf_montecarlo and svf_montecarlo_stderr.");
  return [o, preview, products, check_cells, &app] {
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
    HorizonJob job = prepare_horizon_job(opts, "svf", {preview->path});
    const bool monte_carlo = job.engine->name() == "raycast" && job.engine->params().rays > 0;
    std::vector<std::string> names;
    for (const SvfProductInfo* c : parse_svf_products(*products)) names.push_back(c->name);
    if (monte_carlo) names.insert(names.end(), {"svf_montecarlo", "svf_montecarlo_stderr"});
    const std::size_t drawn = check_preview_options(app, *preview, names);
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
    if (!preview->path.empty()) {
      const auto it = std::find_if(result.bands.begin(), result.bands.end(),
                                   [&](const SvfBand& b) { return b.name == names[drawn]; });
      if (it == result.bands.end())
        throw Error("the preview's band " + names[drawn] + " was not made (internal error)");
      const SvfBand& b = *it;
      write_preview(*preview, b.values, {b.name, b.unit, o->output, job.terrain.georef, {}, {}}, o->out.overwrite);
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
