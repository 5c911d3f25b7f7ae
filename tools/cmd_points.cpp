// skyview points: svf, svf_surface and sky visibility of observers at points of a DSM (CSV or any
// OGR point layer), at a height above the surface, along each observer's own rays.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "command.h"
#include "observer_options.h"
#include "skyview/core/error.h"
#include "skyview/core/lowercase.h"
#include "skyview/core/number_text.h"
#include "skyview/fisheye/horizon_plot.h"
#include "skyview/points/point_query.h"
#include "skyview/raster/raster_io.h"

namespace skyview::cli {
namespace {

struct PointsOptions {
  std::string dsm, points, output, profile_png;
  std::string x_column, y_column, points_crs, layer;
  bool profile = false;
  ObserverOptions observer;
};

int run(const CLI::App& app, const PointsOptions& o) {
  const auto started = std::chrono::steady_clock::now();
  PointQueryOptions q;
  q.height = o.observer.height;
  q.profile = o.profile;
  q.horizons = observer_horizon_options(app, o.observer);
  check_point_output(o.output);
  if (!o.profile_png.empty()) require_extension(o.profile_png, {".png"}, "--profile-png");
  check_outputs_apart({o.output, o.profile_png}, {o.dsm, o.points});
  check_output_writable(o.output, o.observer.overwrite);
  if (!o.profile_png.empty()) check_output_writable(o.profile_png, o.observer.overwrite);
  std::map<std::string, std::string> metadata;
  const Terrain terrain = read_observer_terrain(o.dsm, o.observer, metadata);
  PointTableOptions to;
  to.x_column = o.x_column;
  to.y_column = o.y_column;
  to.crs = o.points_crs;
  to.layer = o.layer;
  const PointTable input = read_point_table(o.points, to, terrain.georef.crs_wkt);
  if (!o.profile_png.empty() && input.rows.size() > kMaxHorizonPlots) {
    throw Error("--profile-png draws at most " + std::to_string(kMaxHorizonPlots) + " points; '" + o.points + "' has " +
                std::to_string(input.rows.size()));
  }
  PointTable table = input;
  transform_points(table, terrain.georef.crs_wkt);
  ProgressCounter progress;
  PointQueryResult result;
  {
    ProgressReporter reporter(progress, o.observer.quiet);
    result = query_points(terrain, table, q, &progress);
  }
  for (std::size_t i = 0; i < result.problem.size(); ++i) {
    if (!result.problem[i].empty())  // even under -q: those rows have no values
      std::fprintf(stderr, "Warning: %s: %s; its values are left empty\n", table.rows[i].where.c_str(),
                   result.problem[i].c_str());
  }
  metadata["SKYVIEW_PRODUCT"] = "points";
  metadata["POINTS"] = o.points;
  metadata["POINTS_FROM"] = input.source;
  metadata["SECTOR_ROTATION_DEG"] = number_text(result.horizons.sector_rotation * 180.0 / M_PI);
  metadata["CURVATURE"] = result.horizons.curvature > 0.0 ? "on" : "off";
  write_point_table(o.output, input, point_result_columns(result, q), std::filesystem::path(o.output).stem().string(),
                    metadata, o.observer.overwrite);
  if (!o.profile_png.empty()) {
    std::vector<HorizonPlot> plots;
    for (std::size_t i = 0; i < result.problem.size(); ++i) {
      HorizonPlot p;
      p.label = input.rows[i].where;
      // Labelled by a name column, else an id column, else the row's place in the input.
      for (const char* wanted : {"name", "id"}) {
        for (std::size_t c = 0; c < input.columns.size() && p.label == input.rows[i].where; ++c) {
          if (lowercase(input.columns[c]) == wanted && !input.rows[i].values[c].empty())
            p.label = input.rows[i].values[c];
        }
      }
      if (result.problem[i].empty()) {
        p.horizons.assign(result.horizons.of(i), result.horizons.of(i) + result.horizons.directions);
        p.svf = result.values[i].svf;
      }
      p.rotation = result.horizons.sector_rotation;
      plots.push_back(std::move(p));
    }
    write_horizon_plots(o.profile_png, plots, o.observer.overwrite);
  }
  if (!o.observer.quiet) {
    double lo = 1.0, hi = 0.0;
    for (std::size_t i = 0; i < result.values.size(); ++i) {
      if (!result.problem[i].empty()) continue;
      lo = std::min(lo, result.values[i].svf);
      hi = std::max(hi, result.values[i].svf);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    std::fprintf(
        stderr, "points: %zu point%s%s at %s m, svf %s, %d directions (%s), %.2f s -> %s\n", result.values.size(),
        result.values.size() == 1 ? "" : "s",
        result.failed ? (" (" + std::to_string(result.failed) + " without values)").c_str() : "",
        number_text(q.height).c_str(),
        result.failed == result.values.size()
            ? "none"
            : (number_text(std::round(lo * 1e4) / 1e4) + " to " + number_text(std::round(hi * 1e4) / 1e4)).c_str(),
        q.horizons.params.directions, q.horizons.method.c_str(), seconds, o.output.c_str());
  }
  return 0;
}

Runner setup(CLI::App& app) {
  auto o = std::make_shared<PointsOptions>();
  app.add_option("dsm", o->dsm, "Elevation raster (DSM; any GDAL format)")->required();
  app.add_option("points", o->points, "Points: CSV with coordinate columns, or any OGR point layer")->required();
  app.add_option("output", o->output, "Output table: .csv or .gpkg (the input's columns plus the results)")->required();
  add_observer_options(app, o->observer, 64);
  app.add_option("--x-column", o->x_column, "CSV column of the x (or longitude) coordinate");
  app.add_option("--y-column", o->y_column, "CSV column of the y (or latitude) coordinate");
  app.add_option("--points-crs", o->points_crs,
                 "CRS of the CSV's coordinates (EPSG:4326, a WKT or PROJ string); default: EPSG:4326 for lon/lat "
                 "columns, otherwise the raster's");
  app.add_option("--layer", o->layer, "Layer of a multi-layer vector file (default: the first)");
  app.add_flag("--profile", o->profile,
               "Add column horizon_deg: each point's horizon angle per direction (degrees) as a JSON array, "
               "direction k at azimuth SECTOR_ROTATION_DEG + 360 k / N");
  app.add_option("--profile-png", o->profile_png,
                 "Also draw each point's horizon as a polar plot (one panel per point, at most 64) into this PNG");
  app.footer(
      "Each point is an observer --height metres above the DSM's surface there (the triangle mesh over cell "
      "centres that every horizon method reads); its horizons are found along its own rays. Output columns: "
      "svf, svf_surface, sky_visibility, ground_m, eye_m, [horizon_deg], error. A point that cannot be evaluated "
      "(outside the raster, on nodata, an unreadable coordinate) is reported on stderr by its line or feature, "
      "keeps its row with the reason in `error`, and the others are computed.");
  return [o, &app] {
    ThreadLimit limit(o->observer.threads);
    return run(app, *o);
  };
}

const Registration reg("points", "svf and sky visibility of observers at points (CSV or vector layer) above a DSM",
                       setup);

}  // namespace
}  // namespace skyview::cli
