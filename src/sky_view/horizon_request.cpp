#include "skyview/sky_view/horizon_request.h"

#include <cmath>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"

namespace skyview {

namespace {

// An option the run would not use is refused: a batch job that asks for --rays 4096 with the
// sweep, or for --max-error and --directions 64 together, would otherwise get an answer to
// another question than it asked, without a word.
void refuse_unused(const HorizonRequest& r, const std::string& option, bool used, const std::string& where) {
  if (!used && r.was_given(option)) throw UsageError(option + " applies only to " + where);
}

// `method` is the one the run uses (--max-error's choice, if given).
void check_options_apply(const HorizonRequest& o, const std::string& method) {
  if (o.max_error >= 0.0) {
    for (const std::string& name : {o.method_option, std::string("--directions"), std::string("--samples"),
                                    std::string("--far-lines"), std::string("--radius"), std::string("--azimuths")}) {
      refuse_unused(o, name, false,
                    "runs without --max-error, which chooses --method, --directions, --samples, --far-lines, "
                    "--radius and --azimuths itself");
    }
  }
  if (o.azimuths == "grid-lines" && o.was_given("--azimuth-origin") && o.azimuth_origin != "grid")
    throw UsageError("--azimuths grid-lines starts on grid north: leave out --azimuth-origin " + o.azimuth_origin);
  const std::string used_by = " (this run uses " + method +
                              (o.params.radius > 0.0 ? " with --radius " + number_text(o.params.radius) : "") + ")";
  const std::string& m = o.method_option;
  refuse_unused(o, "--rays", method == "raycast", m + " raycast" + used_by);
  refuse_unused(o, "--seed", method == "sampled", m + " sampled" + used_by);
  // With a radius the sweep reads every crossing within it: no near steps to count.
  refuse_unused(o, "--samples", method == "sampled" || (method == "sweep" && !(o.params.radius > 0.0)),
                m + " sampled, or sweep at unlimited radius" + used_by);
  refuse_unused(o, "--refraction", method != "raycast" && o.params.curvature != "off",
                "runs with Earth curvature (--curvature on or auto; the ray cast models none)" + used_by);
  refuse_unused(o, "--far-lines", method == "sweep" && !(o.params.radius > 0.0),
                m + " sweep at unlimited radius" + used_by);
  // Along the grid's lines the sweep finds every direction exactly: no near steps, no far lines.
  if (o.azimuths == "grid-lines" && method == "sweep" && !(o.params.radius > 0.0)) {
    for (const char* name : {"--samples", "--far-lines"})
      refuse_unused(o, name, false, "uniform --azimuths (along the grid's lines every direction is exact)");
  }
}

void check_edge_mode(const HorizonSetup& s) {
  if (s.edge == EdgeMode::nodata && std::isinf(s.engine->radius())) {
    throw UsageError(
        std::string("--edge nodata blanks the cells whose search reaches the raster's edge, which with an ") +
        (s.choice ? "unlimited radius (what --max-error chose: it sets --method, --directions, --samples, "
                    "--far-lines and --radius) is every cell; choose the method and --radius yourself"
                  : "unlimited radius is every cell; give --radius"));
  }
}

// --edge nodata with a radius whose circle leaves the raster from every cell would write nodata
// only: refused like the unlimited radius (found from the centre outwards, so a raster where most
// cells fit stops at once).
void check_edge_leaves_cells(const HorizonSetup& s, const Terrain& t, double radius_asked) {
  if (s.edge != EdgeMode::nodata) return;
  const double radius = s.engine->radius();
  if (!search_circle_leaves_raster(t, t.width() / 2, t.height() / 2, radius)) return;
  for (int r = 0; r < t.height(); ++r) {
    for (int c = 0; c < t.width(); ++c) {
      if (t.valid(c, r) && !search_circle_leaves_raster(t, c, r, radius)) return;
    }
  }
  throw UsageError("--edge nodata blanks the cells whose search reaches the raster's edge, which with --radius " +
                   number_text(radius_asked) +
                   " is every cell of this raster; give a smaller --radius or leave --edge open");
}

// A radius shorter than a cell reaches no grid line from any cell centre, where the shared surface
// can rise: every horizon would be open. RVT and SAGA count their radius in cells; here it is metres.
void check_radius_reaches_a_neighbour(const HorizonSetup& s, const Terrain& t, double radius_asked) {
  const double radius = s.engine->radius();
  if (!std::isfinite(radius)) return;
  const double cell = raster_centre_jacobian(t).min_cell_size();
  if (radius >= cell) return;
  throw UsageError("--radius " + number_text(radius_asked) +
                   " m reaches no neighbouring cell (the shorter cell side is " + number_text(cell) +
                   " m), so every horizon would be open; the radius is in metres, not cells");
}

// The metadata of the method that runs (and of --max-error's choice), replacing the last one's.
void record_method(HorizonSetup& s, double max_error, const Terrain& terrain) {
  auto& m = s.metadata;
  for (const std::string& key : s.method_keys) m.erase(key);
  std::map<std::string, std::string> add = s.engine->describe();
  add["CITATION"] = std::string(s.engine->citation());
  // What ran, not what was asked: auto resolves on the raster's extent and the radius.
  const bool curved = s.engine->curvature_coefficient(terrain) > 0.0;
  add["CURVATURE"] = std::string(curved ? "on" : "off") + (s.engine->params().curvature == "auto" ? " (auto)" : "") +
                     (s.engine->name() == "raycast" ? " (the ray cast has none)" : "");
  if (curved) add["REFRACTION"] = number_text(s.engine->params().refraction);
  // The directions too: --max-error's next choice may run along the grid's lines or not.
  s.sector_rotation = direction_set_rotation(s.engine->params(), terrain);
  s.sectors = direction_set(s.engine->params(), terrain);
  const bool grid = direction_set_origin(s.engine->params()) == AzimuthOrigin::grid;
  add["AZIMUTH_ORIGIN"] =
      grid ? "grid: sector 0 centred on grid north at the raster's centre" : "north: sector 0 centred on true north";
  add["AZIMUTHS"] = s.engine->params().spacing == AzimuthSpacing::grid_lines
                        ? "grid-lines: along the grid's columns, rows, diagonals and slope-1/2 lines, each weighted by "
                          "its share of the circle (band metadata SECTOR_WIDTH_DEG in skyview horizon)"
                        : "uniform: every 360/N degrees";
  add["SECTOR_ROTATION_DEG"] = number_text(s.sector_rotation * 180.0 / M_PI);
  if (s.choice) {
    add["MAX_ERROR_REQUESTED"] = number_text(max_error);
    add["MAX_ERROR_CHOICE"] = describe_choice(*s.choice);
    add["MAX_ERROR_CALIBRATED_P99"] = number_text(s.choice->entry.worst_p99);
    add["MAX_ERROR_BASIS"] =
        "worst 99th-percentile |svf error| against the continuous svf (exact horizons in 1024 sectors at 1000 "
        "random cells) over the calibration rasters of docs/benchmarks.md, timed with sectors from grid north";
  }
  s.method_keys.clear();
  for (auto& [k, v] : add) {
    s.method_keys.push_back(k);
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

HorizonSetup plan_horizon(const HorizonRequest& o) {
  if (o.edge != "open" && o.edge != "nodata") throw UsageError("--edge must be open or nodata, not '" + o.edge + "'");
  HorizonSetup s;
  s.edge = o.edge == "nodata" ? EdgeMode::nodata : EdgeMode::open;
  std::string method = o.method;
  HorizonParams params = o.params;
  params.azimuth_origin = azimuth_origin_named(o.azimuth_origin);
  params.spacing = azimuth_spacing_named(o.azimuths);
  if (o.max_error >= 0.0) {
    s.choice = choose_for_max_error(o.max_error, params);
    method = s.choice->method;
    params = s.choice->params;
  }
  check_options_apply(o, method);
  s.engine = make_horizon_engine(method, params);
  check_edge_mode(s);
  return s;
}

void fit_horizon(HorizonSetup& s, const HorizonRequest& o, const Terrain& terrain) {
  check_edge_leaves_cells(s, terrain, o.params.radius);
  check_radius_reaches_a_neighbour(s, terrain, o.params.radius);
  // Auto decides only now, on the raster's reach: a refraction given for rasters where curvature
  // counts is accepted, but said to be unused here.
  if (o.was_given("--refraction") && s.engine->params().curvature == "auto" &&
      !(s.engine->curvature_coefficient(terrain) > 0.0)) {
    s.warnings.push_back(
        "--refraction has no effect: --curvature auto left Earth curvature off on this raster (under 0.01 degrees "
        "at its reach)");
  }
  s.metadata["GROUND_FRAME"] = terrain.frame.description();
  s.metadata["EDGE_MODE"] = o.edge;
  record_method(s, o.max_error, terrain);
  for (auto& [k, v] : horizon_conventions()) s.metadata[k] = v;
}

void use_choice(HorizonSetup& s, const AccuracyChoice& choice, double max_error, const Terrain& terrain) {
  s.choice = choice;
  s.engine = make_horizon_engine(choice.method, choice.params);
  check_edge_mode(s);
  record_method(s, max_error, terrain);
}

void record_edge_cells(HorizonSetup& s, std::int64_t edge_cells) {
  s.metadata["EDGE_CELLS"] = std::to_string(edge_cells);
  if (edge_cells > 0) {
    s.metadata["EDGE_NOTE"] =
        std::to_string(edge_cells) + " cells have search circles leaving the raster; " +
        (s.edge == EdgeMode::open ? "terrain beyond the edge was taken as non-occluding" : "they were set to nodata");
  }
}

std::map<std::string, std::string> horizon_conventions() {
  return {{"NODATA_POLICY", "nodata cells give nodata; nodata inside a search path does not occlude"},
          {"ANGLE_CONVENTION", "elevation above the horizontal; azimuth clockwise from true north"}};
}

}  // namespace skyview
