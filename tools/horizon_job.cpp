#include "horizon_job.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include <optional>

#include "skyview/sky_view/accuracy_choice.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/sky_view/sky_view.h"
#include "skyview/core/version.h"

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
  app.add_option(
         "--method", o.method,
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

// An option the run would not use is refused: a batch job that asks for --rays 4096 with the
// sweep, or for --max-error and --directions 64 together, would otherwise get an answer to
// another question than it asked, without a word.
// `method` is the one the run uses (--max-error's choice, if given).
void check_options_apply(const HorizonJobOptions& o, const std::string& method) {
  if (!o.app) return;
  if (o.max_error >= 0.0) {
    for (const char* name : {"--method", "--directions", "--samples", "--far-lines", "--radius", "--azimuths"}) {
      refuse_unused(*o.app, name, false,
                    "runs without --max-error, which chooses --method, --directions, --samples, --far-lines, "
                    "--radius and --azimuths itself");
    }
  }
  if (o.azimuths == "grid-lines" && o.app->count("--azimuth-origin") > 0 && o.azimuth_origin != "grid")
    throw Error("--azimuths grid-lines starts on grid north: leave out --azimuth-origin " + o.azimuth_origin);
  const std::string used_by = " (this run uses " + method +
                              (o.params.radius > 0.0 ? " with --radius " + number_text(o.params.radius) : "") + ")";
  refuse_unused(*o.app, "--rays", method == "raycast", "--method raycast" + used_by);
  refuse_unused(*o.app, "--seed", method == "sampled", "--method sampled" + used_by);
  // With a radius the sweep reads every crossing within it: no near steps to count.
  refuse_unused(*o.app, "--samples", method == "sampled" || (method == "sweep" && !(o.params.radius > 0.0)),
                "--method sampled, or sweep at unlimited radius" + used_by);
  refuse_unused(*o.app, "--refraction", method != "raycast" && o.params.curvature != "off",
                "runs with Earth curvature (--curvature on or auto; the ray cast models none)" + used_by);
  refuse_unused(*o.app, "--far-lines", method == "sweep" && !(o.params.radius > 0.0),
                "--method sweep at unlimited radius" + used_by);
  // Along the grid's lines the sweep finds every direction exactly: no near steps, no far lines.
  if (o.azimuths == "grid-lines" && method == "sweep" && !(o.params.radius > 0.0)) {
    for (const char* name : {"--samples", "--far-lines"})
      refuse_unused(*o.app, name, false, "uniform --azimuths (along the grid's lines every direction is exact)");
  }
}

void check_edge_mode(const HorizonJob& job) {
  if (job.edge == EdgeMode::nodata && std::isinf(job.engine->radius())) {
    throw Error(std::string("--edge nodata blanks the cells whose search reaches the raster's edge, which with an ") +
                (job.choice ? "unlimited radius (what --max-error chose: it sets --method, --directions, --samples, "
                              "--far-lines and --radius) is every cell; choose the method and --radius yourself"
                            : "unlimited radius is every cell; give --radius"));
  }
}

// --edge nodata with a radius whose circle leaves the raster from every cell would write nodata
// only: refused like the unlimited radius (found from the centre outwards, so a raster where most
// cells fit stops at once).
void check_edge_leaves_cells(const HorizonJob& job, double radius_asked) {
  if (job.edge != EdgeMode::nodata) return;
  const Terrain& t = job.terrain;
  const double radius = job.engine->radius();
  if (!search_circle_leaves_raster(t, t.width() / 2, t.height() / 2, radius)) return;
  for (int r = 0; r < t.height(); ++r) {
    for (int c = 0; c < t.width(); ++c) {
      if (t.valid(c, r) && !search_circle_leaves_raster(t, c, r, radius)) return;
    }
  }
  throw Error("--edge nodata blanks the cells whose search reaches the raster's edge, which with --radius " +
              number_text(radius_asked) +
              " is every cell of this raster; give a smaller --radius or leave --edge open");
}

// A radius shorter than a cell reaches no grid line from any cell centre, where the shared surface
// can rise: every horizon would be open. RVT and SAGA count their radius in cells; here it is metres.
void check_radius_reaches_a_neighbour(const HorizonJob& job, double radius_asked) {
  const double radius = job.engine->radius();
  if (!std::isfinite(radius)) return;
  const double cell = raster_centre_jacobian(job.terrain).min_cell_size();
  if (radius >= cell) return;
  throw Error("--radius " + number_text(radius_asked) + " m reaches no neighbouring cell (the shorter cell side is " +
              number_text(cell) + " m), so every horizon would be open; the radius is in metres, not cells");
}

// The metadata of the method that runs (and of --max-error's choice), replacing the last one's.
void record_method(HorizonJob& job, double max_error) {
  auto& m = job.metadata;
  for (const std::string& key : job.method_keys) m.erase(key);
  std::map<std::string, std::string> add = job.engine->describe();
  add["CITATION"] = std::string(job.engine->citation());
  // What ran, not what was asked: auto resolves on the raster's extent and the radius.
  const bool curved = job.engine->curvature_coefficient(job.terrain) > 0.0;
  add["CURVATURE"] = std::string(curved ? "on" : "off") + (job.engine->params().curvature == "auto" ? " (auto)" : "") +
                     (job.engine->name() == "raycast" ? " (the ray cast has none)" : "");
  if (curved) add["REFRACTION"] = number_text(job.engine->params().refraction);
  // The directions too: --max-error's next choice may run along the grid's lines or not.
  job.sector_rotation = direction_set_rotation(job.engine->params(), job.terrain);
  job.sectors = direction_set(job.engine->params(), job.terrain);
  const bool grid = direction_set_origin(job.engine->params()) == AzimuthOrigin::grid;
  add["AZIMUTH_ORIGIN"] =
      grid ? "grid: sector 0 centred on grid north at the raster's centre" : "north: sector 0 centred on true north";
  add["AZIMUTHS"] = job.engine->params().spacing == AzimuthSpacing::grid_lines
                        ? "grid-lines: along the grid's columns, rows, diagonals and slope-1/2 lines, each weighted by "
                          "its share of the circle (band metadata SECTOR_WIDTH_DEG in skyview horizon)"
                        : "uniform: every 360/N degrees";
  add["SECTOR_ROTATION_DEG"] = number_text(job.sector_rotation * 180.0 / M_PI);
  if (job.choice) {
    add["MAX_ERROR_REQUESTED"] = number_text(max_error);
    add["MAX_ERROR_CHOICE"] = describe_choice(*job.choice);
    add["MAX_ERROR_CALIBRATED_P99"] = number_text(job.choice->entry.worst_p99);
    add["MAX_ERROR_BASIS"] =
        "worst 99th-percentile |svf error| against the continuous svf (exact horizons in 1024 sectors at 1000 "
        "random cells) over the calibration rasters of docs/benchmarks.md, timed with sectors from grid north";
  }
  job.method_keys.clear();
  for (auto& [k, v] : add) {
    job.method_keys.push_back(k);
    m[k] = std::move(v);
  }
}

}  // namespace

std::string describe_choice(const AccuracyChoice& c) {
  if (c.entry.spacing == AzimuthSpacing::grid_lines)
    return c.method + " with " + std::to_string(c.entry.directions) + " directions along the grid's lines";
  return c.method + " with " + std::to_string(c.entry.directions) + " directions" +
         (c.method == "sampled" ? " and " + std::to_string(c.entry.samples) + " samples" : "") +
         (c.method == "sweep"
              ? ", " + std::to_string(c.entry.samples) + " exact near steps and " + std::to_string(c.entry.far_lines) +
                    " far line" + (c.entry.far_lines == 1 ? "" : "s")
              : "");
}

void use_choice(HorizonJob& job, const AccuracyChoice& choice, double max_error) {
  job.choice = choice;
  job.engine = make_horizon_engine(choice.method, choice.params);
  check_edge_mode(job);
  record_method(job, max_error);
}

HorizonJob prepare_horizon_job(const HorizonJobOptions& o, const std::string& command,
                               const std::vector<std::string>& more_outputs) {
  HorizonJob job;
  job.edge = o.edge == "nodata" ? EdgeMode::nodata : EdgeMode::open;
  std::string method = o.method;
  HorizonParams params = o.params;
  params.azimuth_origin = azimuth_origin_named(o.azimuth_origin);
  params.spacing = azimuth_spacing_named(o.azimuths);
  std::optional<AccuracyChoice> choice;
  if (o.max_error >= 0.0) {
    choice = choose_for_max_error(o.max_error, params);
    method = choice->method;
    params = choice->params;
  }
  check_options_apply(o, method);
  job.choice = choice;
  job.engine = make_horizon_engine(method, params);
  check_edge_mode(job);
  // The options first (a user fixing one error should not meet another, older one next), then the
  // outputs, all before the input is read; svf checks its bands' format again.
  std::vector<std::string> outputs{o.output};
  outputs.insert(outputs.end(), more_outputs.begin(), more_outputs.end());
  check_outputs_apart(outputs, {o.input});
  check_output_writable(o.output, o.out.overwrite);
  for (const std::string& path : more_outputs) {
    if (!path.empty()) check_output_writable(path, o.out.overwrite);
  }
  check_output_format(o.output, o.out.format, 1, o.out.creation_options);
  job.quiet = o.out.quiet;
  ReadOptions ro;
  ro.band = o.band;
  ro.z_scale = o.z_scale;
  ReadReport report;
  job.terrain = read_terrain(o.input, ro, &report);
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
  check_edge_leaves_cells(job, params.radius);
  check_radius_reaches_a_neighbour(job, params.radius);
  // Auto decides only now, on the raster's reach: a refraction given for rasters where curvature
  // counts is accepted, but said to be unused here (even under -q: the user asked for it).
  if (o.app && o.app->count("--refraction") > 0 && job.engine->params().curvature == "auto" &&
      !(job.engine->curvature_coefficient(job.terrain) > 0.0)) {
    std::fprintf(stderr,
                 "Warning: --refraction has no effect: --curvature auto left Earth curvature off on '%s' (under "
                 "0.01 degrees at its reach)\n",
                 o.input.c_str());
  }
  m["GROUND_FRAME"] = job.terrain.frame.description();
  m["EDGE_MODE"] = o.edge;
  record_method(job, o.max_error);
  m["NODATA_POLICY"] = "nodata cells give nodata; nodata inside a search path does not occlude";
  m["ANGLE_CONVENTION"] = "elevation above the horizontal; azimuth clockwise from true north";
  return job;
}

void with_progress(const HorizonJob& job, const std::function<void(ProgressCounter&)>& work) {
  ProgressCounter progress;
  progress.set_total(static_cast<std::uint64_t>(job.terrain.width()) * job.terrain.height());
  ProgressReporter reporter(progress, job.quiet);
  work(progress);
}

void record_edge_cells(HorizonJob& job, std::int64_t edge_cells) {
  job.metadata["EDGE_CELLS"] = std::to_string(edge_cells);
  if (edge_cells > 0) {
    job.metadata["EDGE_NOTE"] =
        std::to_string(edge_cells) + " cells have search circles leaving the raster; " +
        (job.edge == EdgeMode::open ? "terrain beyond the edge was taken as non-occluding" : "they were set to nodata");
  }
}

}  // namespace skyview::cli
