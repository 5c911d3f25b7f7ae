// skyview svf: sky-view factor, sky visibility and openness of every cell.
#include <algorithm>
#include <cstdio>
#include <sstream>

#include "skyview/error.h"

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

Runner setup(CLI::App& app) {
  auto o = std::make_shared<HorizonJobOptions>();
  auto preview = std::make_shared<std::string>();
  auto products = std::make_shared<std::string>("svf,svf_surface,sky_visibility,openness_positive,openness_negative");
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
  app.add_option("--preview", *preview, "Also write a greyscale PNG of the svf band (0 black .. 1 white)");
  app.footer(
      "Bands (--products): svf (cosine-weighted, horizontal surface), svf_surface (the cell's tilted surface), "
      "sky_visibility (solid-angle fraction), openness_positive, openness_negative (degrees); raycast with --rays "
      "adds svf_montecarlo and svf_montecarlo_stderr.");
  return [o, preview, products] {
    const std::vector<const ProductBand*> chosen = chosen_products(*products);
    ThreadLimit limit(o->out.threads);
    // Only the products written (and svf for the preview) are summed; negative openness is the only
    // one that needs the lowest angles, a second walk.
    ProductSet keep = ProductSet::none();
    for (const ProductBand* c : chosen) keep.add(c->product);
    if (!preview->empty()) keep.add(Product::svf);
    HorizonJobOptions opts = *o;
    opts.params.lower = keep.has(Product::openness_negative);
    HorizonJob job = prepare_horizon_job(opts, "svf", {*preview});
    if (!preview->empty()) require_extension(*preview, {".png"}, "--preview");
    const bool monte_carlo = job.engine->name() == "raycast" && job.engine->params().rays > 0;
    check_output_format(o->out.format, static_cast<int>(chosen.size()) + (monte_carlo ? 2 : 0),
                        o->out.creation_options);
    // Horizons are held a part at a time (compute_sky_view), so memory does not grow with the
    // number of directions.
    SkyViewProducts p;
    with_progress(job, [&](ProgressCounter& progress) {
      p = compute_sky_view(*job.engine, job.terrain, Window::whole(job.terrain), job.edge, progress, kHorizonBlockBytes,
                           keep);
    });
    job.metadata["EDGE_CELLS"] = std::to_string(p.edge_cells);
    if (p.edge_cells > 0) {
      job.metadata["EDGE_NOTE"] = std::to_string(p.edge_cells) + " cells have search circles leaving the raster; " +
                                  (job.edge == EdgeMode::open ? "terrain beyond the edge was taken as non-occluding"
                                                              : "they were set to nodata");
    }
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
