// skyview render --time: the sun, its shadows and its beam on every pixel of a camera view.
#include "render_sun.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "command.h"
#include "sky_job.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/raster/ground_frame.h"
#include "skyview/raster/raster_site.h"
#include "skyview/sky/exposure_steps.h"
#include "skyview/sky/sky_models.h"
#include "skyview/solar/civil_time.h"
#include "skyview/solar/solar_position.h"
#include "skyview/solar/time_parse.h"

namespace skyview::cli {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

bool has_maps(ShadowMethod m) { return m != ShadowMethod::exact; }
bool has_cascades(ShadowMethod m) { return m == ShadowMethod::csm || m == ShadowMethod::hsm; }
bool has_layers(ShadowMethod m) { return m == ShadowMethod::lvsm || m == ShadowMethod::hsm; }

ShadowOptions options_for(const RenderSunOptions& o, ShadowMethod method) {
  ShadowOptions s = o.shadow;
  s.soft = o.soft;
  if (o.layers) (method == ShadowMethod::hsm ? s.hsm_layers : s.layers) = *o.layers;
  return s;
}

// The library names its fields (map_size, cascades, layers); the command line its options.
[[noreturn]] void rethrow_as_option(const UsageError& e) {
  static const std::pair<const char*, const char*> names[] = {{"map_size", "--shadow-map-size"},
                                                              {"cascades", "--cascades"},
                                                              {"hsm_layers", "--layers"},
                                                              {"layers", "--layers"}};
  const std::string what = e.what();
  for (const auto& [field, option] : names) {
    const std::string prefix = std::string(field) + ":";
    if (what.rfind(prefix, 0) == 0) throw UsageError(option + what.substr(prefix.size() - 1));
  }
  throw;
}

// Azimuth of true north on the scene's grid (radians, clockwise from +y) at its centre: a
// projected CRS's grid north is off true north by the meridian convergence.
double grid_azimuth_of_true(double true_azimuth, const Scene& scene, double cx, double cy) {
  if (scene.crs_wkt.empty()) return true_azimuth;
  GeoReference g;
  g.has_geotransform = true;
  g.crs_wkt = scene.crs_wkt;
  g.geotransform = {cx - 0.5, 1, 0, cy + 0.5, 0, -1};  // one 1 m cell centred on the scene's centre
  const Jacobian j = GroundFrame(g, 1, 1).at(0, 0);
  double dcol = 0, drow = 0;
  j.pixel_step_for_azimuth(true_azimuth, dcol, drow);
  return std::atan2(dcol, -drow);
}

}  // namespace

void add_render_sun_options(CLI::App& app, RenderSunOptions& o) {
  app.add_option("--time", o.time,
                 "Sun shadows at this instant, ISO 8601 with offset or zone (as skyview shadow): adds the bands "
                 "sunlit (or sun_fraction) and direct_now");
  app.add_option("--tz", o.tz, "IANA zone for --time without an offset");
  app.add_option("--lat", o.lat, "Latitude of the sun's site, degrees north (default: the scene's centre)");
  app.add_option("--lon", o.lon, "Longitude of the sun's site, degrees east (default: the scene's centre)");
  app.add_option("--elevation", o.elevation,
                 "Elevation of the sun's site above sea level, metres (default: the scene's lowest point)");
  app.add_option("--shadows", o.shadows, "How shadows are found: exact (shadow rays), pcf, vsm, lvsm, csm or hsm")
      ->check(CLI::IsMember({"exact", "pcf", "vsm", "lvsm", "csm", "hsm"}))
      ->capture_default_str();
  app.add_flag("--soft", o.soft,
               "With --shadows exact: band sun_fraction, the visible share of the sun's disc, instead of sunlit");
  app.add_option("--shadow-map-size", o.shadow.map_size, "Texels on the longer side of each shadow map")
      ->capture_default_str();
  app.add_option("--cascades", o.shadow.cascades, "Cascades of csm and hsm")->capture_default_str();
  app.add_option("--layers", o.layers, "Depth layers of lvsm (default 8) and of each hsm cascade (default 7)");
  app.add_option("--turbidity", o.turbidity,
                 "Turbidity of the Preetham clear sky whose beam gives direct_now (2 .. 10)")
      ->capture_default_str();
}

void check_render_sun_options(const CLI::App& app, RenderSunOptions& o) {
  const bool timed = !o.time.empty();
  for (const char* name : {"--tz", "--lat", "--lon", "--elevation", "--shadows", "--soft", "--shadow-map-size",
                           "--cascades", "--layers", "--turbidity"}) {
    refuse_unused(app, name, timed, "runs with --time");
  }
  if (!timed) return;
  if (!o.tz.empty()) check_time_zone(o.tz);
  parse_time_option(o.time, o.tz);
  const ShadowMethod method = parse_shadow_method(o.shadows);
  refuse_unused(app, "--soft", method == ShadowMethod::exact, "--shadows exact");
  refuse_unused(app, "--shadow-map-size", has_maps(method), "the shadow-map methods (not --shadows exact)");
  refuse_unused(app, "--cascades", has_cascades(method), "--shadows csm and hsm");
  refuse_unused(app, "--layers", has_layers(method), "--shadows lvsm and hsm");
  if (!(o.turbidity >= 2.0 && o.turbidity <= 10.0))
    throw UsageError("--turbidity must be within 2 .. 10 (the Preetham sky's range)");
  ShadowOptions s = options_for(o, method);
  s.eye = Vec3f{0, 0, 0};  // the camera's, known later; only its presence is checked
  try {
    validate_shadow_options(method, s);
  } catch (const UsageError& e) {
    rethrow_as_option(e);
  }
}

std::string sun_band_name(const RenderSunOptions& o) { return o.soft ? "sun_fraction" : "sunlit"; }

RenderSunBands render_sun(const RenderSunOptions& o, const Scene& scene, const RayScene& rays, const ViewBuffers& view,
                          const Vec3d& eye) {
  const ParsedTime when = parse_time_option(o.time, o.tz);
  const auto [lo, hi] = scene.bounds();
  const double cx = scene.origin[0] + 0.5 * (lo[0] + hi[0]), cy = scene.origin[1] + 0.5 * (lo[1] + hi[1]);
  std::optional<GeoPoint> centre;
  if (!o.lat && !o.lon && !scene.crs_wkt.empty()) {
    GeoReference g;
    g.has_geotransform = true;
    g.crs_wkt = scene.crs_wkt;
    g.geotransform = {cx - 0.5, 1, 0, cy + 0.5, 0, -1};
    centre = raster_centre_geographic(g, 1, 1);
  }
  std::string source;
  const Site site =
      sun_site(centre, scene.origin[2] + lo[2], "the scene", "the scene's centre", o.lat, o.lon, o.elevation, source);
  const SunPosition sun = solar_position(when.unix_utc, site);
  require_sun_up(sun, when.unix_utc, site);
  const double grid_azimuth = grid_azimuth_of_true(sun.azimuth_deg * kDegree, scene, cx, cy);
  const Vec3f s = sun_direction_of(grid_azimuth, sun.elevation_deg * kDegree);

  // Receivers: the pixels that see the scene.
  const std::size_t n = view.position.size();
  ShadowReceivers receivers;
  std::vector<std::size_t> pixel;
  for (std::size_t i = 0; i < n; ++i) {
    if (!view.hit(i)) continue;
    receivers.points.push_back(view.position[i]);
    receivers.normals.push_back(view.normal[i]);
    pixel.push_back(i);
  }
  const ShadowMethod method = parse_shadow_method(o.shadows);
  ShadowOptions so = options_for(o, method);
  so.eye = Vec3f{static_cast<float>(eye[0]), static_cast<float>(eye[1]), static_cast<float>(eye[2])};
  const ShadowResult shade = sun_visibility(rays, scene, s, receivers, method, so);

  SkyConditions c;
  c.sun_zenith = sun.zenith_deg * kDegree;
  c.sun_azimuth = sun.azimuth_deg * kDegree;
  c.day_of_year = day_of_year_utc(when.unix_utc);
  const double dni = make_preetham_sky(o.turbidity)->at(c)->direct_normal();

  RenderSunBands out;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  out.visibility.assign(n, nan);
  out.direct_now.assign(n, nan);
  double lit = 0;
  for (std::size_t k = 0; k < pixel.size(); ++k) {
    const Vec3f& nv = receivers.normals[k];
    const double cosi = std::max(0.0, double(nv[0]) * s[0] + double(nv[1]) * s[1] + double(nv[2]) * s[2]);
    const float v = shade.visibility[k];
    out.visibility[pixel[k]] = v;
    out.direct_now[pixel[k]] = static_cast<float>(dni * cosi * v);
    lit += v;
  }
  auto& m = out.metadata;
  add_sun_instant_metadata(m, o.time, o.tz, when.unix_utc, site, source, sun);
  m["SUN_GRID_AZIMUTH_DEG"] = number_text(grid_azimuth / kDegree);
  m["SHADOW_METHOD"] = shadow_method_name(method);
  if (has_maps(method)) {
    m["SHADOW_MAP_SIZE"] = std::to_string(so.map_size);
    m["SHADOW_MAPS"] = std::to_string(shade.maps);
    m["SHADOW_MAP_MIB"] = number_text(std::round(shade.map_bytes / 1048576.0 * 100) / 100);
  }
  if (has_cascades(method)) m["SHADOW_CASCADES"] = std::to_string(so.cascades);
  if (has_layers(method)) m["SHADOW_LAYERS"] = std::to_string(method == ShadowMethod::hsm ? so.hsm_layers : so.layers);
  if (o.soft) m["SHADOW_SOFT_SAMPLES"] = std::to_string(so.soft_samples);
  m["SHADOW_MAP_SECONDS"] = number_text(std::round(shade.map_seconds * 1e4) / 1e4);
  m["SHADOW_LOOKUP_SECONDS"] = number_text(std::round(shade.lookup_seconds * 1e4) / 1e4);
  m["DIRECT_NORMAL_W_M2"] = number_text(std::round(dni * 10) / 10);
  m["DIRECT_SKY"] = "preetham, turbidity " + number_text(o.turbidity) +
                    " (Rayleigh + Angstrom aerosol transmittance of a 5778 K sun, docs/sky.md)";
  char what[200];
  std::snprintf(what, sizeof what, "sun at azimuth %.2f, elevation %.2f deg; %.1f%% of pixels sunlit (%s)",
                sun.azimuth_deg, sun.elevation_deg, pixel.empty() ? 0.0 : 100.0 * lit / pixel.size(),
                shadow_method_name(method).c_str());
  out.summary = what;
  return out;
}

}  // namespace skyview::cli
