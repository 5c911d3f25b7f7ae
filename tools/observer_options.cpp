#include "observer_options.h"

#include <cstdio>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/core/version.h"
#include "skyview/raster/raster_io.h"

namespace skyview::cli {

void add_observer_options(CLI::App& app, ObserverOptions& o, int directions) {
  o.horizons.params.directions = directions;
  o.horizons.params.radius = 0.0;
  app.add_option("-b,--band", o.band, "Input band")->capture_default_str();
  app.add_option("--z-scale", o.z_scale,
                 "Metres per height unit (0.3048 for feet); default: the band's unit or vertical CRS, else metres")
      ->check(positive_number());
  app.add_option("--height", o.height, "Eye height above the surface at the point, metres")
      ->check(non_negative_number())
      ->capture_default_str();
  app.add_option("--method", o.method,
                 "march (every row and column crossing along each observer's own rays, exact on the surface mesh) "
                 "or raycast (Embree rays, the reference; needs --height above 0)")
      ->check(CLI::IsMember({"march", "raycast"}))
      ->capture_default_str();
  CLI::Option* dirs =
      app.add_option("--directions", o.horizons.params.directions,
                     directions > 0 ? "Number of azimuth directions (uniform sectors)"
                                    : "Number of azimuth directions (uniform sectors); default: one per pixel of the "
                                      "picture's rim, a power of two")
          ->check(CLI::Range(1, 65536));
  if (directions > 0) dirs->capture_default_str();
  app.add_option("--radius", o.horizons.params.radius, "Search radius in metres (default: to the raster's edge)")
      ->check(positive_number());
  app.add_option("--curvature", o.horizons.params.curvature, "Earth curvature: auto, on, off")
      ->check(CLI::IsMember({"auto", "on", "off"}))
      ->capture_default_str();
  app.add_option("--refraction", o.horizons.params.refraction, "Refraction coefficient with curvature")
      ->check(finite_number())
      ->capture_default_str();
  app.add_option("--azimuth-origin", o.azimuth_origin,
                 "Centre of the first direction: north (true north) or grid (grid north at the raster's centre)")
      ->check(CLI::IsMember({"north", "grid"}))
      ->capture_default_str();
  app.add_flag("--overwrite", o.overwrite, "Replace existing outputs");
  app.add_flag("-q,--quiet", o.quiet, "No progress or summary on stderr (warnings and errors still)");
  app.add_option("--threads", o.threads, "Worker threads (0 = all cores)")->check(non_negative_number());
}

PointHorizonOptions observer_horizon_options(const CLI::App& app, const ObserverOptions& o) {
  PointHorizonOptions h = o.horizons;
  h.method = o.method;
  h.params.azimuth_origin = azimuth_origin_named(o.azimuth_origin);
  refuse_unused(app, "--refraction", o.method == "march" && h.params.curvature != "off",
                "runs with Earth curvature (--curvature on or auto; the ray cast models none)");
  if (o.method == "raycast" && !(o.height > 0.0))
    throw Error("--method raycast needs observers above the surface: give --height above 0");
  if (o.method == "raycast" && h.params.curvature == "on")
    throw Error("--method raycast models no Earth curvature; use --curvature off");
  return h;
}

Terrain read_observer_terrain(const std::string& path, const ObserverOptions& o,
                              std::map<std::string, std::string>& m) {
  ReadOptions ro;
  ro.band = o.band;
  ro.z_scale = o.z_scale;
  ReadReport report;
  Terrain t = read_terrain(path, ro, &report);
  if (report.undeclared_nan_cells > 0) {
    std::fprintf(stderr, "Warning: %lld NaN cells in '%s' are not the declared nodata value; treated as nodata\n",
                 static_cast<long long>(report.undeclared_nan_cells), path.c_str());
  }
  m["SKYVIEW_VERSION"] = version();
  m["SKYVIEW_COMMAND"] = command_line();
  m["SOURCE"] = path;
  m["SOURCE_BAND"] = std::to_string(o.band);
  m["Z_SCALE"] = number_text(report.z_scale);
  m["HEIGHT_UNIT"] = report.height_unit;
  m["OBSERVER_HEIGHT_M"] = number_text(o.height);
  m["METHOD"] = o.method;
  m["DIRECTIONS"] = std::to_string(o.horizons.params.directions);
  m["RADIUS_M"] = o.horizons.params.radius > 0.0 ? number_text(o.horizons.params.radius) : "unlimited";
  m["CITATION"] = o.method == "march"
                      ? "exhaustive line march over every cell crossing along each observer's own rays"
                      : "Embree 3 rays on a triangle mesh over cell centres, horizon bracketed to 1e-5 rad";
  return t;
}

}  // namespace skyview::cli
