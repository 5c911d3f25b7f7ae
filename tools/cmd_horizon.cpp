// skyview horizon: horizon elevation angle per direction, one band per azimuth.
#include <cmath>
#include <limits>
#include <sstream>

#include "horizon_job.h"

namespace skyview::cli {
namespace {

Runner setup(CLI::App& app) {
  auto o = std::make_shared<HorizonJobOptions>();
  add_horizon_job_options(app, *o);
  app.footer("One band per direction, in degrees above the horizontal; band k is centred on azimuth 360*k/N.");
  return [o] {
    ThreadLimit limit(o->out.threads);
    HorizonJobOptions opts = *o;
    opts.params.rays = 0;  // the ray cast's Monte-Carlo svf is not a horizon band
    HorizonJob job = run_horizon_job(opts, "horizon");
    const int w = job.terrain.width(), h = job.terrain.height(), n = job.field.directions;
    std::vector<std::vector<float>> planes(n, std::vector<float>(static_cast<std::size_t>(w) * h));
    for (int r = 0; r < h; ++r) {
      for (int c = 0; c < w; ++c) {
        const std::size_t cell = job.field.cell(c, r);
        const bool drop =
            !job.terrain.valid(c, r) ||
            (job.edge == EdgeMode::nodata && search_circle_leaves_raster(job.terrain, c, r, job.engine->radius()));
        for (int k = 0; k < n; ++k) {
          planes[k][cell] = drop ? std::numeric_limits<float>::quiet_NaN()
                                 : static_cast<float>(job.field.upper_at(cell, k) * 180.0 / M_PI);
        }
      }
    }
    std::vector<OutputBand> bands;
    for (int k = 0; k < n; ++k) {
      std::ostringstream name, az;
      az << 360.0 * k / n;
      name << "horizon_azimuth_" << az.str();
      bands.push_back({name.str(), "degree", planes[k].data(), {{"AZIMUTH_DEG", az.str()}}});
    }
    WriteOptions wo;
    wo.format = o->out.format;
    wo.creation_options = o->out.creation_options;
    wo.overwrite = o->out.overwrite;
    wo.metadata = job.metadata;
    if (job.engine->name() == "sampled") {
      wo.metadata["AZIMUTH_NOTE"] = "sampled rotates each cell's direction set randomly within +-half a sector";
    }
    write_bands(o->output, w, h, job.terrain.georef, bands, wo);
    return 0;
  };
}

const Registration reg("horizon", "Horizon angle per direction (one band per azimuth) from a DEM/DSM", setup);

}  // namespace
}  // namespace skyview::cli
