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
    HorizonJob job = prepare_horizon_job(opts, "horizon");
    const int w = job.terrain.width(), h = job.terrain.height(), n = job.engine->params().directions;
    const Window whole = Window::whole(job.terrain);
    std::vector<unsigned char> blank(whole.cells());  // cells written as nodata
    for (int r = 0; r < h; ++r) {
      for (int c = 0; c < w; ++c) {
        blank[static_cast<std::size_t>(r) * w + c] =
            !job.terrain.valid(c, r) ||
            (job.edge == EdgeMode::nodata && search_circle_leaves_raster(job.terrain, c, r, job.engine->radius()));
      }
    }
    WriteOptions wo;
    wo.format = o->out.format;
    wo.creation_options = o->out.creation_options;
    wo.overwrite = o->out.overwrite;
    wo.metadata = job.metadata;
    if (job.engine->name() == "sampled") {
      wo.metadata["AZIMUTH_NOTE"] = "sampled rotates each cell's direction set randomly within +-half a sector";
    }
    // Bands are written as the directions are found: the sweep, which finds one at a time, holds
    // only those in progress, so memory does not grow with the number of directions.
    BandWriter out(o->output, w, h, n, job.terrain.georef, wo);
    std::vector<float> degrees(blank.size());
    auto write_direction = [&](int k, const float* radians) {
      for (std::size_t i = 0; i < degrees.size(); ++i) {
        degrees[i] = blank[i] ? std::numeric_limits<float>::quiet_NaN() : static_cast<float>(radians[i] * 180.0 / M_PI);
      }
      std::ostringstream name, az;
      az << 360.0 * k / n;
      name << "horizon_azimuth_" << az.str();
      out.write(k, {name.str(), "degree", degrees.data(), {{"AZIMUTH_DEG", az.str()}}});
    };
    HorizonField field;
    with_progress(job, [&](ProgressCounter& progress) {
      if (job.engine->streams_directions()) {
        job.engine->compute_directions(job.terrain, whole, field, progress,
                                       [&](int first, int count, const float* upper, const float*) {
                                         for (int j = 0; j < count; ++j)
                                           write_direction(first + j, upper + whole.cells() * j);
                                       });
      } else {
        job.engine->compute(job.terrain, whole, field, progress);
        for (int k = 0; k < n; ++k) write_direction(k, field.upper_plane(k));
      }
    });
    out.finish();
    return 0;
  };
}

const Registration reg("horizon", "Horizon angle per direction (one band per azimuth) from a DEM/DSM", setup);

}  // namespace
}  // namespace skyview::cli
