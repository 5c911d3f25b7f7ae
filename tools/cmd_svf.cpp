// skyview svf: sky-view factor, sky visibility and openness of every cell.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/sky_view/svf_check.h"

#include "horizon_job.h"

namespace skyview::cli {
namespace {

// The bands `skyview svf` can write, in their default order.
struct ProductBand {
  const char* name;
  const char* unit;
  const char* definition;
  Product product;
};
constexpr ProductBand kProducts[] = {
    {"svf", "1", "1 - mean sin^2(max(h,0)); cosine-weighted, horizontal", Product::svf},
    {"svf_surface", "1", "view factor of the tilted cell surface (Horn normal) to the unobstructed sky",
     Product::svf_surface},
    {"sky_visibility", "1", "1 - mean sin(max(h,0)); solid-angle fraction of the hemisphere", Product::sky_visibility},
    {"openness_positive", "degree", "mean zenith angle of the horizon (Yokoyama 2002)", Product::openness_positive},
    {"openness_negative", "degree", "mean nadir angle of the lowest terrain (Yokoyama 2002)",
     Product::openness_negative},
};

std::vector<const ProductBand*> chosen_products(const std::string& list) {
  std::vector<const ProductBand*> out;
  std::stringstream in(list);
  for (std::string name; std::getline(in, name, ',');) {
    const auto* it =
        std::find_if(std::begin(kProducts), std::end(kProducts), [&](const ProductBand& p) { return name == p.name; });
    if (it == std::end(kProducts)) {
      throw Error("unknown product '" + name +
                  "' (svf, svf_surface, sky_visibility, openness_positive, openness_negative)");
    }
    if (std::find(out.begin(), out.end(), it) != out.end()) throw Error("'" + name + "' given twice");
    out.push_back(it);
  }
  if (out.empty()) throw Error("no product given");
  return out;
}

// Cells the svf check samples by default with --max-error: the p99 of 1000 cells is within about
// 20% of the raster's, and their exact horizons cost a fraction of a second on the samples.
constexpr int kDefaultCheckCells = 1000;

std::string four_digits(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", v);
  return text;
}

// The fewest cells whose p99 bounds the raster's with 95% confidence (299: 0.99^n must fall
// under 0.05); fewer cells give a p99 but no bound.
int cells_for_a_bound() {
  static const int cells = [] {
    int n = 1;
    while (quantile_upper_rank(n, 0.99, 0.95) == 0) ++n;
    return n;
  }();
  return cells;
}

std::string bound_text(double bound) {
  return std::isnan(bound) ? "none under " + std::to_string(cells_for_a_bound()) + " cells" : four_digits(bound);
}

SvfCheckOptions check_options(const HorizonJob& job, int cells) {
  SvfCheckOptions c;
  c.cells = cells;
  c.directions = std::max(64, job.engine->params().directions);
  c.curvature = job.engine->curvature_coefficient(job.terrain);
  c.azimuth_origin = job.engine->params().azimuth_origin;
  return c;
}

void record_check(HorizonJob& job, const SvfCheck& check, const SvfCheckResult& r) {
  auto& m = job.metadata;
  m["SVF_CHECK_CELLS"] = std::to_string(r.error.cells);
  m["SVF_CHECK_P99"] = number_text(r.error.p99);
  if (std::isnan(r.p99_upper95)) {
    m.erase("SVF_CHECK_P99_UPPER95");  // under 300 cells bound no p99
  } else {
    m["SVF_CHECK_P99_UPPER95"] = number_text(r.p99_upper95);
  }
  m["SVF_CHECK_MAX"] = number_text(r.error.max_abs);
  m["SVF_CHECK_RMSE"] = number_text(r.error.rmse);
  m["SVF_CHECK_BIAS"] = number_text(r.error.bias);
  m["SVF_CHECK_P99_FINE"] = number_text(r.error_fine.p99);
  if (std::isnan(r.fine_p99_upper95)) {
    m.erase("SVF_CHECK_P99_FINE_UPPER95");
  } else {
    m["SVF_CHECK_P99_FINE_UPPER95"] = number_text(r.fine_p99_upper95);
  }
  m["SVF_CHECK_BASIS"] =
      "svf - exact svf on " + std::string(r.exhaustive ? "every valid cell" : "random valid cells") +
      " (the march over every row and column crossing to the raster's edge, " + std::to_string(check.directions()) +
      " sectors, the run's curvature); P99_UPPER95 bounds the raster's p99 with 95% confidence; P99_FINE is against " +
      std::to_string(check.fine_directions()) +
      " sectors, near the continuous svf, and adds the sectors' own error (what --max-error is held to)";
}

Runner setup(CLI::App& app) {
  auto o = std::make_shared<HorizonJobOptions>();
  auto preview = std::make_shared<std::string>();
  auto check_cells = std::make_shared<int>(-1);
  auto products = std::make_shared<std::string>("svf,svf_surface,sky_visibility,openness_positive,openness_negative");
  o->azimuth_origin = "grid";  // every band sums over azimuth
  add_horizon_job_options(app, *o);
  app.add_option("--products", *products,
                 "Bands to write, in this order; without openness_negative the lowest angles are not computed "
                 "(about half the sweep's time)")
      ->capture_default_str()
      ->check(CLI::Validator(
          [](std::string& list) {
            try {
              chosen_products(list);
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
  app.add_option("--preview", *preview,
                 "Also write a greyscale PNG of the svf band (0 black .. 1 white, nodata transparent)");
  app.footer(
      "Bands (--products): svf (cosine-weighted, horizontal surface), svf_surface (the cell's tilted surface), "
      "sky_visibility (solid-angle fraction), openness_positive, openness_negative (degrees); raycast with --rays "
      "adds svf_montecarlo and svf_montecarlo_stderr.");
  return [o, preview, products, check_cells] {
    const std::vector<const ProductBand*> chosen = chosen_products(*products);
    ThreadLimit limit(o->out.threads);
    // Only the products written (and svf for the preview) are summed; negative openness is the only
    // one that needs the lowest angles, a second walk.
    ProductSet keep = ProductSet::none();
    for (const ProductBand* c : chosen) keep.add(c->product);
    const int n_check = *check_cells >= 0 ? *check_cells : (o->max_error >= 0.0 ? kDefaultCheckCells : 0);
    // --max-error is met by a 95% bound of the p99, which fewer cells cannot give (a raster with
    // fewer valid cells is checked whole, and needs none).
    if (o->max_error >= 0.0 && n_check > 0 && n_check < cells_for_a_bound()) {
      throw Error("--check-cells " + std::to_string(n_check) + " cannot show that --max-error is met: a 95% bound of " +
                  "the p99 needs " + std::to_string(cells_for_a_bound()) + " cells or more (or 0: no check)");
    }
    if (!preview->empty() || n_check > 0) keep.add(Product::svf);
    HorizonJobOptions opts = *o;
    opts.params.lower = keep.has(Product::openness_negative);
    HorizonJob job = prepare_horizon_job(opts, "svf", {*preview});
    if (!preview->empty()) require_extension(*preview, {".png"}, "--preview");
    const bool monte_carlo = job.engine->name() == "raycast" && job.engine->params().rays > 0;
    check_output_format(o->output, o->out.format, static_cast<int>(chosen.size()) + (monte_carlo ? 2 : 0),
                        o->out.creation_options);
    if (n_check > 0 && job.engine->params().directions > kSvfCheckMaxDirections) {
      throw Error("--check-cells measures against the run's own sectors, at most " +
                  std::to_string(kSvfCheckMaxDirections) + " (this run has --directions " +
                  std::to_string(job.engine->params().directions) + "); use fewer directions or leave it out");
    }
    // Horizons are held a part at a time (compute_sky_view), so memory does not grow with the
    // number of directions.
    SkyViewProducts p;
    std::optional<SvfCheck> check;
    std::string tried;  // --max-error's runs and what the check measured
    for (;;) {
      with_progress(job, [&](ProgressCounter& progress) {
        p = compute_sky_view(*job.engine, job.terrain, Window::whole(job.terrain), job.edge, progress,
                             kHorizonBlockBytes, keep);
      });
      if (n_check == 0) break;
      const SvfCheckOptions co = check_options(job, n_check);
      if (!check || check->directions() != co.directions || check->curvature() != co.curvature)
        check.emplace(job.terrain, co);
      const SvfCheckResult r = check->measure(p.svf);
      record_check(job, *check, r);
      if (!o->out.quiet) {
        std::fprintf(stderr,
                     "svf check on %lld cells (%.1f s): p99 %s (95%% bound %s), max %s, bias %+.4f against exact "
                     "horizons in %d sectors; p99 %s (95%% bound %s) against %d sectors, near the continuous svf\n",
                     static_cast<long long>(r.error.cells), check->seconds(), four_digits(r.error.p99).c_str(),
                     bound_text(r.p99_upper95).c_str(), four_digits(r.error.max_abs).c_str(), r.error.bias,
                     check->directions(), four_digits(r.error_fine.p99).c_str(), bound_text(r.fine_p99_upper95).c_str(),
                     check->fine_directions());
      }
      if (!job.choice) break;
      // The request is met when the raster's p99 against the near-continuous svf (the finer
      // sectors, the calibration's basis) is within it with 95% confidence: the bound, not the
      // sample's own p99, which on a 100² city read 0.0092 where all cells gave 0.0105.
      const double requested = o->max_error;
      const double bound = std::isnan(r.fine_p99_upper95) ? r.error_fine.max_abs : r.fine_p99_upper95;
      tried += (tried.empty() ? "" : "; ") + describe_choice(*job.choice) + ": p99 " + four_digits(r.error_fine.p99) +
               ", bound " + four_digits(bound);
      job.metadata["MAX_ERROR_MEASURED_P99"] = number_text(r.error_fine.p99);
      job.metadata["MAX_ERROR_MEASURED_BOUND"] = number_text(bound);
      job.metadata["MAX_ERROR_MET"] =
          bound > requested ? "no" : (r.exhaustive ? "yes (every valid cell checked)" : "yes (with 95% confidence)");
      job.metadata["MAX_ERROR_TRIED"] = tried;
      // The parts of the error, where the check's sectors are the run's own.
      MeasuredError measured;
      measured.bound = bound;
      if (check->directions() == job.choice->params.directions) {
        measured.method_p99 = r.error.p99;
        measured.sector_p99 = check->sector_p99();
      }
      const auto next = choose_after_measurement(requested, job.choice->entry, measured, job.choice->params);
      if (!next) {
        if (bound > requested) {
          std::fprintf(stderr,
                       "Warning: --max-error %s not met: the svf check bounds the p99 by %s with %s, the most "
                       "accurate calibrated choice\n",
                       number_text(requested).c_str(), four_digits(bound).c_str(),
                       describe_choice(*job.choice).c_str());
        }
        break;
      }
      if (!o->out.quiet) {
        std::fprintf(stderr, "--max-error %s: the svf check bounds the p99 by %s with %s; running again with %s\n",
                     number_text(requested).c_str(), four_digits(bound).c_str(), describe_choice(*job.choice).c_str(),
                     describe_choice(*next).c_str());
      }
      use_choice(job, *next, requested);
    }
    record_edge_cells(job, p.edge_cells);
    WriteOptions wo;
    wo.format = o->out.format;
    wo.creation_options = o->out.creation_options;
    wo.overwrite = o->out.overwrite;
    wo.metadata = job.metadata;
    const int w = job.terrain.width(), h = job.terrain.height();
    std::vector<OutputBand> bands;
    for (const ProductBand* c : chosen)
      bands.push_back({c->name, c->unit, (p.*product_grid(c->product)).data(), {{"DEFINITION", c->definition}}});
    if (!p.svf_montecarlo.values().empty()) {
      bands.push_back({"svf_montecarlo",
                       "1",
                       p.svf_montecarlo.data(),
                       {{"DEFINITION", "fraction of stratified cosine-weighted rays that reach the sky"}}});
      bands.push_back({"svf_montecarlo_stderr",
                       "1",
                       p.svf_montecarlo_stderr.data(),
                       {{"DEFINITION", "binomial standard error of svf_montecarlo (an upper bound)"}}});
    }
    write_bands(o->output, w, h, job.terrain.georef, bands, wo);
    if (!preview->empty()) write_preview_png(*preview, w, h, p.svf.data(), 0.0, 1.0, o->out.overwrite);
    return 0;
  };
}

const Registration reg("svf", "Sky-view factor, sky visibility and openness GeoTIFF from a DEM/DSM", setup);

}  // namespace
}  // namespace skyview::cli
