// skyview horizon: horizon elevation angle per direction, one band per azimuth.
#include <cmath>
#include <limits>
#include <string>

#include "horizon_job.h"
#include "skyview/core/number_text.h"
#include "skyview/sky_view/horizon_bands.h"

namespace skyview::cli {
namespace {

Runner setup(CLI::App& app) {
  auto o = std::make_shared<HorizonJobOptions>();
  add_horizon_job_options(app, *o);
  app.footer(
      "One band per direction, in degrees above the horizontal; band k is centred on azimuth 360*k/N (plus "
      "SECTOR_ROTATION_DEG with --azimuth-origin grid; with --azimuths grid-lines on the grid's lines); each band's "
      "AZIMUTH_DEG says where and SECTOR_WIDTH_DEG how wide an angle it stands for.");
  return [o, &app] {
    const RunSummary summary("horizon");
    refuse_unused(app, "--rays", false, "skyview svf (its Monte-Carlo svf bands)");
    ThreadLimit limit(o->out.threads);
    HorizonJobOptions opts = *o;
    opts.params.rays = 0;  // the ray cast's Monte-Carlo svf is not a horizon band
    HorizonJob job = prepare_horizon_job(opts, "horizon");
    const int w = job.terrain.width(), h = job.terrain.height(), n = job.engine->params().directions;
    const Window whole = Window::whole(job.terrain);
    std::int64_t edge_cells = 0;
    const std::vector<unsigned char> blank = horizon_blank_cells(job, job.terrain, edge_cells);  // written as nodata
    record_edge_cells(job, edge_cells);
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
    // block. Memory does not grow with the number of directions.
    if (!job.engine->streams_directions()) wo.rows_at_once = rows_in_budget(*job.engine, w, kHorizonBlockBytes);
    BandWriter out(o->output, w, h, n, job.terrain.georef, wo);
    const std::vector<DirectionBand> directions = direction_bands(job);
    for (int k = 0; k < n; ++k) {
      const DirectionBand& d = directions[static_cast<std::size_t>(k)];
      out.describe(k, {"horizon_azimuth_" + d.azimuth_deg,
                       "degree",
                       nullptr,
                       {{"AZIMUTH_DEG", d.azimuth_deg}, {"SECTOR_WIDTH_DEG", number_text(d.width_deg)}}});
    }
    std::vector<float> degrees;
    // Rows [row0, row0 + rows) of direction k from its plane of radians over those rows.
    auto write_rows = [&](int k, int row0, int rows, const float* radians) {
      const std::size_t first = static_cast<std::size_t>(row0) * w, count = static_cast<std::size_t>(rows) * w;
      degrees.resize(count);
      for (std::size_t i = 0; i < count; ++i) {
        degrees[i] =
            blank[first + i] ? std::numeric_limits<float>::quiet_NaN() : static_cast<float>(radians[i] * 180.0 / M_PI);
      }
      out.write_rows(k, row0, rows, degrees.data());
    };
    with_progress(job, [&](ProgressCounter& progress) {
      if (job.engine->streams_directions()) {
        HorizonField rest;
        job.engine->compute_directions(job.terrain, whole, rest, progress,
                                       [&](int first, int count, const float* upper, const float*) {
                                         for (int j = 0; j < count; ++j)
                                           write_rows(first + j, 0, h, upper + whole.cells() * j);
                                       });
      } else {
        compute_by_row_blocks(*job.engine, job.terrain, whole, progress, kHorizonBlockBytes, out.block_rows(),
                              [&](const Window& block, HorizonField& field) {
                                for (int k = 0; k < n; ++k) write_rows(k, block.row0, block.rows, field.upper_plane(k));
                              });
      }
    });
    out.finish();
    summary.print(std::to_string(w) + "x" + std::to_string(h) + " cells, " + std::to_string(n) +
                      " direction bands by " + std::string(job.engine->name()) + "; " + std::to_string(edge_cells) +
                      " cells whose search leaves the raster",
                  o->out.quiet);
    return 0;
  };
}

const Registration reg("horizon", "Horizon angle per direction (one band per azimuth) from a DEM/DSM", setup);

}  // namespace
}  // namespace skyview::cli
