// skyview horizon: horizon elevation angle per direction, one band per azimuth.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "horizon_job.h"
#include "preview_options.h"
#include "skyview/core/number_text.h"

namespace skyview::cli {
namespace {

Runner setup(CLI::App& app) {
  auto o = std::make_shared<HorizonJobOptions>();
  auto preview = std::make_shared<PreviewOptions>();
  add_horizon_job_options(app, *o);
  add_preview_options(app, *preview,
                      "Also write a PNG of the first direction's band, or --preview-band's (horizon_azimuth_90)");
  app.footer(
      "One band per direction, in degrees above the horizontal; band k is centred on azimuth 360*k/N (plus "
      "SECTOR_ROTATION_DEG with --azimuth-origin grid; with --azimuths grid-lines on the grid's lines); each band's "
      "AZIMUTH_DEG says where and SECTOR_WIDTH_DEG how wide an angle it stands for.");
  return [o, preview, &app] {
    const RunSummary summary("horizon");
    refuse_unused(app, "--rays", false, "skyview svf (its Monte-Carlo svf bands)");
    ThreadLimit limit(o->out.threads);
    HorizonJobOptions opts = *o;
    opts.params.rays = 0;  // the ray cast's Monte-Carlo svf is not a horizon band
    HorizonJob job = prepare_horizon_job(opts, "horizon", {preview->path});
    const int w = job.terrain.width(), h = job.terrain.height(), n = job.engine->params().directions;
    const Window whole = Window::whole(job.terrain);
    std::vector<unsigned char> blank(whole.cells());  // cells written as nodata
    std::int64_t edge_cells = 0;
    for (int r = 0; r < h; ++r) {
      for (int c = 0; c < w; ++c) {
        const bool valid = job.terrain.valid(c, r);
        const bool leaves = valid && search_circle_leaves_raster(job.terrain, c, r, job.engine->radius());
        edge_cells += leaves;
        blank[static_cast<std::size_t>(r) * w + c] = !valid || (job.edge == EdgeMode::nodata && leaves);
      }
    }
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
    const double rotation = job.sector_rotation * 180.0 / M_PI;
    const bool uniform = job.sectors.is_uniform();  // named by 360 k / N, as before grid lines
    std::vector<std::string> names, azimuths;
    std::vector<double> widths;
    for (int k = 0; k < n; ++k) {
      // In [0, 360) to ten significant digits: a set turned by -0.0001° starts at 359.9998961, and
      // a residue that rounds to 360 reads 0.
      const double offset = uniform ? 360.0 * k / n : job.sectors.offset[static_cast<std::size_t>(k)] * 180.0 / M_PI;
      double azimuth = std::fmod(offset + rotation, 360.0);
      if (azimuth < 0.0) azimuth += 360.0;
      std::string az = number_text(azimuth);
      if (std::stod(az) >= 360.0) az = "0";
      widths.push_back(uniform ? 360.0 / n : 360.0 * job.sectors.share[static_cast<std::size_t>(k)]);
      azimuths.push_back(az);
      names.push_back("horizon_azimuth_" + az);
    }
    const int drawn = static_cast<int>(check_preview_options(app, *preview, names));
    Grid<float> drawn_values;
    if (!preview->path.empty()) drawn_values = Grid<float>(w, h);
    BandWriter out(o->output, w, h, n, job.terrain.georef, wo);
    for (int k = 0; k < n; ++k) {
      const std::size_t i = static_cast<std::size_t>(k);
      out.describe(
          k,
          {names[i], "degree", nullptr, {{"AZIMUTH_DEG", azimuths[i]}, {"SECTOR_WIDTH_DEG", number_text(widths[i])}}});
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
      if (k == drawn && drawn_values.size() > 0) std::copy(degrees.begin(), degrees.end(), drawn_values.data() + first);
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
    write_preview(*preview, drawn_values,
                  {names[static_cast<std::size_t>(drawn)], "degree", o->output, job.terrain.georef, {}, {}},
                  o->out.overwrite);
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
