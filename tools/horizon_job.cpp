#include "horizon_job.h"
#include "far_field_job.h"
#include "far_field_pyramid.h"
#include "tile_ranks.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include <optional>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/core/version.h"
#include "skyview/sky_view/sky_view.h"
#include "skyview/tiling/tile_grid.h"

namespace skyview::cli {

void add_horizon_job_options(CLI::App& app, HorizonJobOptions& o) {
  o.app = &app;
  app.add_option("input", o.input, "Input elevation raster (any GDAL format)")->required();
  app.add_option("output", o.output, "Output raster")->required();
  app.add_option("-b,--band", o.band, "Input band")->capture_default_str();
  app.add_option(
         "--z-scale", o.z_scale,
         "Metres per height unit (0.3048 for feet); default: the band's unit or vertical CRS, else metres if the "
         "CRS is in metres or degrees")
      ->check(positive_number());
  app.add_option("--s_srs", o.s_srs,
                 "The input's CRS where it carries none or a wrong one (EPSG:25833, a WKT or PROJ string), as "
                 "gdal_translate -a_srs states it; without any CRS coordinates are taken as metres");
  app.add_option(
         o.method_option, o.method,
         "Horizon method: sweep (hull sweep, unlimited radius or --radius), march, sampled, raycast (Embree reference)")
      ->capture_default_str();
  app.add_option("--directions", o.params.directions, "Number of azimuth directions")->capture_default_str();
  app.add_option("--samples", o.params.samples,
                 "Per direction: samples (sampled, default 16) or exact near steps (sweep, default 64); 0 = default")
      ->capture_default_str();
  app.add_option("--far-lines", o.params.far_lines,
                 "Sweep beyond its near steps: tangent to the hull of the nearer line beside a cell (1), or to both "
                 "lines' hulls, interpolated (2: slower, about as accurate as 1 with twice the near steps)")
      ->check(CLI::IsMember({1, 2}))
      ->capture_default_str();
  app.add_option(
         "--radius", o.params.radius,
         "Search radius in metres (march and sampled: default 500; sweep: unlimited, or every crossing within it)")
      ->check(positive_number());
  app.add_option("--rays", o.params.rays, "Monte-Carlo rays per cell for the direct svf (raycast only; 0 = none)")
      ->capture_default_str();
  app.add_option("--seed", o.params.seed, "Seed of the per-cell rotation (sampled only)")->capture_default_str();
  app.add_option("--edge", o.edge,
                 "open: terrain beyond the raster does not occlude; nodata: cells whose search circle leaves the "
                 "raster get nodata")
      ->check(CLI::IsMember({"open", "nodata"}))
      ->capture_default_str();
  app.add_option("--curvature", o.params.curvature, "Earth curvature: auto, on, off")
      ->check(CLI::IsMember({"auto", "on", "off"}))
      ->capture_default_str();
  app.add_option("--refraction", o.params.refraction, "Refraction coefficient with curvature")
      ->capture_default_str()
      ->check(finite_number());
  app.add_option("--azimuth-origin", o.azimuth_origin,
                 "Centre of the first sector: north (true north), or grid (grid north at the raster's centre, so that "
                 "sectors at multiples of 45 degrees run along rows, columns and diagonals, which the sweep finds "
                 "exactly and about 2.8 times faster; svf and openness sum over azimuth and do not depend on it "
                 "beyond the sectors' own error)")
      ->check(CLI::IsMember({"north", "grid"}))
      ->capture_default_str();
  app.add_option("--azimuths", o.azimuths,
                 "Where the directions point: uniform (every 360/N degrees), or grid-lines (4, 8 or 16 directions "
                 "along the raster's columns, rows, diagonals and lines of slope 1/2, from grid north: 0, 26.57, "
                 "45, 63.43, ... degrees on square cells, each weighted by the share of the circle it stands for; "
                 "the sweep finds them all exactly: 16 of them 1.1-1.5 times faster than uniform, for about 1.3 "
                 "times the svf error)")
      ->check(CLI::IsMember({"uniform", "grid-lines"}))
      ->capture_default_str();
  app.add_option("--max-error", o.max_error,
                 "Choose the cheapest method and parameters whose calibrated 99th-percentile error against the "
                 "continuous svf (sector discretisation included) is below this; it sets --method, --directions, "
                 "--samples, --far-lines, --radius and --azimuths, which are then refused")
      ->check(number_above(0.0, 1.0));
  app.add_flag("!--no-early-exit", o.params.early_exit,
               "Disable early termination (march and sampled: the max-height pyramid; sweep: skipped far-field "
               "searches); same results");
  add_output_options(app, o.out);
}

namespace {

// Every option that the library's checks refuse when the run would not use it.
const char* const kCheckedOptions[] = {"--directions", "--samples", "--far-lines",  "--radius",        "--azimuths",
                                       "--rays",       "--seed",    "--refraction", "--azimuth-origin"};

}  // namespace

HorizonRequest horizon_request(const HorizonJobOptions& o) {
  HorizonRequest r;
  r.method = o.method;
  r.method_option = o.method_option;
  r.edge = o.edge;
  r.max_error = o.max_error;
  r.azimuth_origin = o.azimuth_origin;
  r.azimuths = o.azimuths;
  r.params = o.params;
  if (o.app) {
    if (o.app->count(o.method_option) > 0) r.given.insert(o.method_option);
    for (const char* name : kCheckedOptions) {
      if (o.app->count(name) > 0) r.given.insert(name);
    }
  }
  return r;
}

void use_choice(HorizonJob& job, const AccuracyChoice& choice, double max_error) {
  skyview::use_choice(job, choice, max_error, job.terrain);
}

HorizonJob prepare_horizon_job(const HorizonJobOptions& o, const std::string& command,
                               const std::vector<std::string>& more_outputs, const TileRequest* tiling) {
  const HorizonRequest request = horizon_request(o);
  HorizonJob job;
  static_cast<HorizonSetup&>(job) = plan_horizon(request);
  // The options first (a user fixing one error should not meet another, older one next), then the
  // outputs, all before the input is read; svf checks its bands' format again.
  std::vector<std::string> outputs{o.output};
  outputs.insert(outputs.end(), more_outputs.begin(), more_outputs.end());
  check_outputs_apart(outputs, {o.input});
  check_output_writable(o.output, o.out.overwrite);
  for (const std::string& path : more_outputs) {
    if (!path.empty()) check_output_writable(path, o.out.overwrite);
  }
  const bool mosaic = tiling && !tiling->options.tiles_dir.empty();
  if (!mosaic) check_output_format(o.output, o.out.format, 1, o.out.creation_options);
  if (tiling) check_tiling_options(tiling->options, o.output, o.out.format);
  job.quiet = o.out.quiet || TileRanks::world().rank() > 0;  // progress from rank 0 alone
  if (tiling && TileRanks::world().parallel() && tiling->options.tiles_dir.empty())
    throw UsageError("under mpirun the ranks share the tiles of a --tiles-dir run: give --tiles-dir");
  ReadOptions ro;
  ro.band = o.band;
  ro.z_scale = o.z_scale;
  ro.assign_crs = o.s_srs;
  ReadReport report;
  if (tiling) {
    const RasterSize size = raster_size(o.input, o.band);
    job.tiles = plan_tiles(*tiling, *job.engine, size.width, size.height);
    if (!tiling->options.tiles_dir.empty()) {  // a far field's pyramid is kept there, for reruns
      job.tiles.pyramid_file = (std::filesystem::path(tiling->options.tiles_dir) / kPyramidFileName).string();
      job.tiles.pyramid_source = nlohmann::json{
          {"input", input_identity(o.input)},
          {"band", o.band},
          {"z_scale", o.z_scale},
          {"s_srs", o.s_srs}}.dump();
    }
  }
  if (job.tiles.tiled) {
    job.reader = std::make_shared<TerrainReader>(o.input, ro, &report);
    const int w = job.reader->width(), h = job.reader->height();
    if (!std::isfinite(job.engine->radius()))
      prepare_far_field(job, tiling->far_error >= 0 ? tiling->far_error : o.max_error);
    choose_tile_size(job.tiles, *tiling, *job.engine, job.reader->frame(), w, h);
    // The checks that need the raster look at its centre: a window there as wide as a tile's halo
    // (the cell farthest from every edge is the centre's).
    const Window centre = with_halo({w / 2, h / 2, 1, 1}, std::max(1, std::min(job.tiles.halo, 256)), w, h);
    job.terrain = job.reader->read(centre);
  } else {
    job.terrain = read_terrain(o.input, ro, &report);
  }
  if (report.undeclared_nan_cells > 0) {  // even under -q: it changes what the data say
    std::fprintf(stderr, "Warning: %lld NaN cells in '%s' are not the declared nodata value; treated as nodata\n",
                 static_cast<long long>(report.undeclared_nan_cells), o.input.c_str());
  }
  auto& m = job.metadata;
  m["SKYVIEW_VERSION"] = version();
  m["SKYVIEW_COMMAND"] = command_line();
  m["SKYVIEW_PRODUCT"] = command;
  m["SOURCE"] = o.input;
  m["SOURCE_BAND"] = std::to_string(o.band);
  m["Z_SCALE"] = number_text(report.z_scale);
  m["HEIGHT_UNIT"] = report.height_unit;
  fit_horizon(job, request, job.terrain);
  if (job.far_field) {
    m["RADIUS_M"] = "unlimited (exact within the halo of FAR_FIELD_HALO_M, the far field beyond)";
  }
  for (const std::string& w : job.warnings) std::fprintf(stderr, "Warning: %s ('%s')\n", w.c_str(), o.input.c_str());
  job.warnings.clear();
  return job;
}

void with_progress(const HorizonJob& job, const std::function<void(ProgressCounter&)>& work) {
  ProgressCounter progress;
  progress.set_total(static_cast<std::uint64_t>(job.width()) * job.height());
  ProgressReporter reporter(progress, job.quiet);
  work(progress);
}

}  // namespace skyview::cli
