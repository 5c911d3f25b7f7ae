// skyview svf: sky-view factor, sky visibility and openness of every cell.
#include <cstdio>

#include "horizon_job.h"

namespace skyview::cli {
namespace {

Runner setup(CLI::App& app) {
  auto o = std::make_shared<HorizonJobOptions>();
  auto preview = std::make_shared<std::string>();
  add_horizon_job_options(app, *o);
  app.add_option("--preview", *preview, "Also write a greyscale PNG of the svf band (0 black .. 1 white)");
  app.footer(
      "Bands: 1 svf (cosine-weighted, horizontal surface), 2 svf_surface (the cell's tilted surface), "
      "3 sky_visibility (solid-angle fraction), 4 openness_positive, 5 openness_negative (degrees).");
  return [o, preview] {
    if (!preview->empty()) check_output_writable(*preview, o->out.overwrite);
    ThreadLimit limit(o->out.threads);
    HorizonJobOptions opts = *o;
    opts.params.lower = true;  // negative openness needs the lowest angles
    HorizonJob job = prepare_horizon_job(opts, "svf");
    // Horizons are held a part at a time (compute_sky_view), so memory does not grow with the
    // number of directions.
    SkyViewProducts p;
    with_progress(job, [&](ProgressCounter& progress) {
      p = compute_sky_view(*job.engine, job.terrain, Window::whole(job.terrain), job.edge, progress);
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
    std::vector<OutputBand> bands{
        {"svf", "1", p.svf.data(), {{"DEFINITION", "1 - mean sin^2(max(h,0)); cosine-weighted, horizontal"}}},
        {"svf_surface",
         "1",
         p.svf_surface.data(),
         {{"DEFINITION", "view factor of the tilted cell surface (Horn normal) to the unobstructed sky"}}},
        {"sky_visibility",
         "1",
         p.sky_visibility.data(),
         {{"DEFINITION", "1 - mean sin(max(h,0)); solid-angle fraction of the hemisphere"}}},
        {"openness_positive",
         "degree",
         p.openness_positive.data(),
         {{"DEFINITION", "mean zenith angle of the horizon (Yokoyama 2002)"}}},
        {"openness_negative",
         "degree",
         p.openness_negative.data(),
         {{"DEFINITION", "mean nadir angle of the lowest terrain (Yokoyama 2002)"}}}};
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
