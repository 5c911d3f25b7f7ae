// skyview fisheye: the hemisphere seen from a point at a height above a DSM, as an upward-looking
// fish-eye camera photographs it, and its binary sky mask for skyview fisheye-svf.
#include <gdal.h>
#include <ogr_spatialref.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "command.h"
#include "observer_options.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/fisheye/fisheye_view.h"
#include "skyview/raster/raster_io.h"
#include "skyview/solar/solar_position.h"

namespace skyview::cli {
namespace {

struct FisheyeOptions {
  std::string dsm, output, mask, at, at_lonlat, time, tz, projection = "equidistant";
  int size = 1024;
  bool mirror = false;
  double turbidity = 3.0;
  ObserverOptions observer;
};

// "X,Y" as two finite numbers.
void parse_pair(const std::string& text, const std::string& option, double& a, double& b) {
  const std::size_t comma = text.find(',');
  std::size_t used_a = 0, used_b = 0;
  try {
    if (comma == std::string::npos) throw std::invalid_argument("");
    a = std::stod(text.substr(0, comma), &used_a);
    b = std::stod(text.substr(comma + 1), &used_b);
  } catch (const std::exception&) {
    throw Error(option + " must be two numbers separated by a comma, not '" + text + "'");
  }
  if (used_a != comma || used_b != text.size() - comma - 1 || !std::isfinite(a) || !std::isfinite(b))
    throw Error(option + " must be two numbers separated by a comma, not '" + text + "'");
}

// Transforms (x, y) between a CRS given as WKT and WGS 84 longitude/latitude.
void lonlat_transform(const std::string& wkt, double& x, double& y, bool to_lonlat) {
  OGRSpatialReference crs, wgs84;
  if (wkt.empty() || crs.importFromWkt(wkt.c_str()) != OGRERR_NONE)
    throw Error(std::string(to_lonlat ? "--time" : "--at-lonlat") +
                " needs a raster with a CRS (to place the point on the Earth); this one has none");
  wgs84.importFromEPSG(4326);
  crs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> ct(
      OGRCreateCoordinateTransformation(to_lonlat ? &crs : &wgs84, to_lonlat ? &wgs84 : &crs));
  if (!ct || !ct->Transform(1, &x, &y)) throw Error("cannot transform the point between the raster's CRS and lon/lat");
}

int run(const CLI::App& app, FisheyeOptions o) {
  const auto started = std::chrono::steady_clock::now();
  require_extension(o.output, {".png"}, "The fish-eye picture");
  if (o.mask.empty()) {
    const std::filesystem::path p(o.output);
    o.mask = (p.parent_path() / (p.stem().string() + "_mask.png")).string();
  }
  require_extension(o.mask, {".png"}, "--mask");
  if (o.at.empty() == o.at_lonlat.empty()) throw Error("give the point with --at X,Y or --at-lonlat LON,LAT");
  refuse_unused(app, "--tz", !o.time.empty(), "--time");
  refuse_unused(app, "--turbidity", !o.time.empty(), "--time (the Preetham sky)");
  FisheyeViewOptions v;
  v.size = o.size;
  v.projection = projection_named(o.projection);
  v.mirror = o.mirror;
  v.horizons = observer_horizon_options(app, o.observer);
  v.directions = app.count("--directions") ? o.observer.horizons.params.directions : 0;
  if (o.observer.method != "march") throw Error("skyview fisheye draws with the march's distances: --method march");
  if (!o.time.empty() && !(o.turbidity >= 2.0 && o.turbidity <= 10.0))
    throw Error("--turbidity must be within 2 .. 10 (the Preetham sky's range)");
  double px = 0, py = 0;
  if (!o.at.empty())
    parse_pair(o.at, "--at", px, py);
  else
    parse_pair(o.at_lonlat, "--at-lonlat", px, py);
  std::optional<ParsedTime> when;
  if (!o.time.empty()) when = parse_time_option(o.time, o.tz);
  check_outputs_apart({o.output, o.mask}, {o.dsm});
  check_output_writable(o.output, o.observer.overwrite);
  check_output_writable(o.mask, o.observer.overwrite);
  std::map<std::string, std::string> metadata;
  const Terrain terrain = read_observer_terrain(o.dsm, o.observer, metadata);
  if (!o.at_lonlat.empty()) lonlat_transform(terrain.georef.crs_wkt, px, py, false);
  double inverse[6];
  if (!GDALInvGeoTransform(const_cast<double*>(terrain.georef.geotransform.data()), inverse))
    throw Error("the raster's geotransform cannot be inverted");
  const Observer observer{inverse[0] + px * inverse[1] + py * inverse[2] - 0.5,
                          inverse[3] + px * inverse[4] + py * inverse[5] - 0.5, o.observer.height};
  if (when) {
    double lon = px, lat = py;
    lonlat_transform(terrain.georef.crs_wkt, lon, lat, true);
    Site site;
    site.latitude_deg = lat;
    site.longitude_deg = lon;
    const SunPosition sun = solar_position(when->unix_utc, site);
    if (sun.elevation_deg <= 0.0) {
      std::fprintf(stderr, "Warning: the sun is %.1f degrees below the horizon at %s; drawing a plain sky\n",
                   -sun.elevation_deg, o.time.c_str());
    } else {
      v.sun = SunForView{sun.zenith_deg * M_PI / 180.0, sun.azimuth_deg * M_PI / 180.0, o.turbidity};
    }
  }
  const FisheyeView view = fisheye_view(terrain, observer, v);
  if (!view.problem.empty()) {
    throw Error("the point (" + number_text(px) + ", " + number_text(py) + ") is " + view.problem + " of '" + o.dsm +
                "'");
  }
  write_png(o.output, view.size, view.size, 3, view.rgb.data(), o.observer.overwrite);
  write_png(o.mask, view.size, view.size, 1, view.mask.data(), o.observer.overwrite);
  if (!o.observer.quiet) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    std::fprintf(stderr,
                 "fisheye: svf %.4f, sky visibility %.4f at %s m above ground (%.2f m), %s, %d directions, %.2f s "
                 "-> %s, %s\n",
                 view.values.svf, view.values.sky_visibility, number_text(o.observer.height).c_str(),
                 view.horizons.ground[0], o.projection.c_str(), view.horizons.directions, seconds, o.output.c_str(),
                 o.mask.c_str());
  }
  return 0;
}

Runner setup(CLI::App& app) {
  auto o = std::make_shared<FisheyeOptions>();
  app.add_option("dsm", o->dsm, "Elevation raster (DSM; any GDAL format)")->required();
  app.add_option("output", o->output, "The picture, PNG")->required();
  app.add_option("--at", o->at, "The point, X,Y in the raster's CRS")->type_name("X,Y");
  app.add_option("--at-lonlat", o->at_lonlat, "The point as longitude,latitude (WGS 84)")->type_name("LON,LAT");
  add_observer_options(app, o->observer, 0);
  app.add_option("--projection", o->projection, "equidistant, equisolid, orthographic or stereographic")
      ->check(CLI::IsMember({"equidistant", "equisolid", "orthographic", "stereographic"}))
      ->capture_default_str();
  app.add_option("--size", o->size, "Width and height of the picture in pixels; the 90 degree circle fills it")
      ->check(CLI::Range(64, 8192))
      ->capture_default_str();
  app.add_option("--time", o->time,
                 "Draw the Preetham sky and the sun for this instant (ISO 8601 with offset or zone, e.g. "
                 "2024-06-21T12:00+02:00); default: a plain sky");
  app.add_option("--tz", o->tz, "IANA zone for a --time without offset, e.g. Europe/Stockholm");
  app.add_option("--turbidity", o->turbidity, "Turbidity of the Preetham sky (2 .. 10)")->capture_default_str();
  app.add_flag("--mirror", o->mirror,
               "East on the right (a map of the sky seen from above) instead of on the left (as a camera looking "
               "up sees it)");
  app.add_option("--mask", o->mask, "The binary sky mask, PNG (255 = sky); default: OUTPUT's name with _mask");
  app.footer(
      "The picture shows what a camera looking straight up with a circular fish-eye lens records: north at the "
      "top, east on the left (--mirror: on the right). The 90 degree circle is inscribed in the square picture; "
      "the mask has the same geometry, so `skyview fisheye-svf OUT_mask.png --mask` reads it back. --directions "
      "defaults to one direction per pixel of the rim (a power of two, at least 64).");
  return [o, &app] {
    ThreadLimit limit(o->observer.threads);
    return run(app, *o);
  };
}

const Registration reg("fisheye", "Fish-eye picture of the sky seen from a point above a DSM, and its sky mask", setup);

}  // namespace
}  // namespace skyview::cli
