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
#include "skyview/raster/output_files.h"
#include "skyview/raster/raster_site.h"
#include "skyview/render/colour_view.h"
#include "skyview/render/shadow_difference.h"
#include "skyview/render/shadow_error.h"
#include "skyview/sky/exposure_map.h"
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
  app.add_option("--colour-out", o.colour_out,
                 "Also write the view in colour at --time (PNG): the clear sky and the sun's disc behind the city, "
                 "grey surfaces lit by global_now, one fixed tone mapping for every instant");
  app.add_option("--shadow-diff", o.shadow_diff,
                 "With a shadow-map method: a PNG of its differences from exact shadow rays (leaks red, acne blue, "
                 "agreement grey)");
}

void check_render_sun_options(const CLI::App& app, RenderSunOptions& o) {
  const bool timed = !o.time.empty();
  for (const char* name : {"--tz", "--lat", "--lon", "--elevation", "--shadows", "--soft", "--shadow-map-size",
                           "--cascades", "--layers", "--turbidity", "--colour-out", "--shadow-diff"}) {
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
  refuse_unused(app, "--shadow-diff", has_maps(method), "the shadow-map methods (not --shadows exact)");
  if (!o.colour_out.empty()) require_extension(o.colour_out, {".png"}, "--colour-out");
  if (!o.shadow_diff.empty()) require_extension(o.shadow_diff, {".png"}, "--shadow-diff");
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

SunInstant place_sun(const RenderSunOptions& o, const Scene& scene) {
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
  SunInstant s;
  s.unix_utc = when.unix_utc;
  s.site = sun_site(centre, scene.origin[2] + lo[2], "the scene", "the scene's centre", o.lat, o.lon, o.elevation,
                    s.site_source);
  s.position = solar_position(when.unix_utc, s.site);
  require_sun_up(s.position, when.unix_utc, s.site);
  s.grid_azimuth = grid_azimuth_of_true(s.position.azimuth_deg * kDegree, scene, cx, cy);
  s.direction = sun_direction_of(s.grid_azimuth, s.position.elevation_deg * kDegree);
  s.conditions.sun_zenith = s.position.zenith_deg * kDegree;
  s.conditions.sun_azimuth = s.grid_azimuth;
  s.conditions.day_of_year = day_of_year_utc(when.unix_utc);
  s.direct_normal = make_preetham_sky(o.turbidity)->at(s.conditions)->direct_normal();
  return s;
}

namespace {

ExposureMap instant_map(const RenderSunOptions& o, const SunInstant& sun, int width, int height) {
  const ExposureStep step{sun.conditions, 1.0};  // one hour: Wh becomes W
  ExposureOptions eo;
  eo.width = width;
  eo.height = height;
  return integrate_exposure(*make_preetham_sky(o.turbidity), std::span<const ExposureStep>(&step, 1), eo);
}

}  // namespace

InstantSky::InstantSky(const RenderSunOptions& o, const SunInstant& sun, int directions)
    : width_(std::max(512, directions)),
      height_(256),
      diffuse_horizontal_(make_preetham_sky(o.turbidity)->at(sun.conditions)->diffuse_horizontal()),
      pyramid_(instant_map(o, sun, width_, height_)),
      sampler_(pyramid_, directions) {}

std::vector<float> diffuse_now_of(const TwoScaleBands& bands) {
  std::vector<float> out(bands.exposure_diffuse.values().begin(), bands.exposure_diffuse.values().end());
  for (float& v : out) v *= 1000.0f;  // kWh over one hour to W
  return out;
}

RenderSunBands render_sun(const RenderSunOptions& o, const SunInstant& sun, const InstantSky& sky, const Scene& scene,
                          const RayScene& rays, const ViewBuffers& view, const Vec3d& eye,
                          std::vector<float> diffuse_now) {
  const Vec3f s = sun.direction;
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
  const double dni = sun.direct_normal;

  RenderSunBands out;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  out.visibility.assign(n, nan);
  out.direct_now.assign(n, nan);
  out.diffuse_now = std::move(diffuse_now);
  out.global_now.assign(n, nan);
  double lit = 0;
  for (std::size_t k = 0; k < pixel.size(); ++k) {
    const Vec3f& nv = receivers.normals[k];
    const double cosi = std::max(0.0, double(nv[0]) * s[0] + double(nv[1]) * s[1] + double(nv[2]) * s[2]);
    const float v = shade.visibility[k];
    const std::size_t i = pixel[k];
    out.visibility[i] = v;
    out.direct_now[i] = static_cast<float>(dni * cosi * v);
    out.global_now[i] = out.direct_now[i] + out.diffuse_now[i];
    lit += v;
  }
  auto& m = out.metadata;
  add_sun_instant_metadata(m, o.time, o.tz, sun.unix_utc, sun.site, sun.site_source, sun.position);
  m["SUN_GRID_AZIMUTH_DEG"] = number_text(sun.grid_azimuth / kDegree);
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
  std::string error_text;
  if (has_maps(method)) {
    // The exact rays on the same receivers: the method's error in this very view.
    const ShadowResult exact = sun_visibility(rays, scene, s, receivers, ShadowMethod::exact, so);
    const ShadowError e = shadow_error(rays, s, receivers, exact, shade, so);
    out.exact.assign(n, nan);
    for (std::size_t k = 0; k < pixel.size(); ++k) out.exact[pixel[k]] = exact.visibility[k];
    auto pct = [&](std::size_t c) { return number_text(std::round(100 * e.share(c) * 1e4) / 1e4); };
    m["SHADOW_EXACT_SECONDS"] = number_text(std::round(exact.seconds() * 1e4) / 1e4);
    m["SHADOW_ERROR_RECEIVERS"] = std::to_string(e.receivers);
    m["SHADOW_ERROR_WRONG_PCT"] = pct(e.wrong);
    m["SHADOW_ERROR_EDGES_PCT"] = pct(e.wrong_edge);
    m["SHADOW_ERROR_INTERIORS_PCT"] = pct(e.wrong_interior);
    m["SHADOW_ERROR_LEAKS_PCT"] = pct(e.leaks);
    m["SHADOW_ERROR_ACNE_PCT"] = pct(e.acne);
    m["SHADOW_ERROR_EDGE_RECEIVERS_PCT"] = pct(e.edge_receivers);
    m["SHADOW_ERROR_MEAN_ABS"] = number_text(std::round(e.mean_abs * 1e6) / 1e6);
    m["SHADOW_ERROR_DEFINITION"] =
        "percent of the pixels on the scene whose sunlit state (visibility >= 0.5) differs from exact shadow rays': "
        "EDGES within two map texels of the exact shadow's boundary, INTERIORS elsewhere; LEAKS sunlit where the "
        "rays see shadow, ACNE shadow where they see the sun (docs/shadows.md)";
    char text[120];
    std::snprintf(text, sizeof text, "; %.2f%% wrong against exact rays (%.2f%% leaks, %.2f%% acne)",
                  100 * e.wrong_share(), 100 * e.share(e.leaks), 100 * e.share(e.acne));
    error_text = text;
  }
  m["DIRECT_NORMAL_W_M2"] = number_text(std::round(dni * 10) / 10);
  m["DIRECT_SKY"] = "preetham, turbidity " + number_text(o.turbidity) +
                    " (Rayleigh + Angstrom aerosol transmittance of a 5778 K sun, docs/sky.md)";
  m["DIFFUSE_HORIZONTAL_W_M2"] = number_text(std::round(sky.diffuse_horizontal() * 10) / 10);
  m["DIFFUSE_SKY"] = "preetham, turbidity " + number_text(o.turbidity) +
                     " (luminance / 125 lm/W), as an exposure map of the instant " + std::to_string(sky.map_width()) +
                     "x" + std::to_string(sky.map_height()) + " read through the two-scale visibility";
  char what[200];
  std::snprintf(what, sizeof what, "sun at azimuth %.2f, elevation %.2f deg; %.1f%% of pixels sunlit (%s)",
                sun.position.azimuth_deg, sun.position.elevation_deg, pixel.empty() ? 0.0 : 100.0 * lit / pixel.size(),
                shadow_method_name(method).c_str());
  out.summary = what + error_text;
  return out;
}

void write_render_sun_pictures(const RenderSunOptions& o, const SunInstant& sun, const RenderSunBands& bands,
                               const Camera& camera, const ViewBuffers& view, bool overwrite) {
  if (!o.colour_out.empty()) {
    ColourViewOptions co;
    co.turbidity = o.turbidity;
    const ColourViewSun cs{sun.conditions.sun_zenith, sun.grid_azimuth, sun.direct_normal};
    const std::vector<std::uint8_t> rgb = colour_view(camera, view, bands.global_now, cs, co);
    write_png(o.colour_out, view.width, view.height, 3, rgb.data(), overwrite);
  }
  if (!o.shadow_diff.empty()) {
    const std::vector<std::uint8_t> rgb = shadow_difference_picture(bands.visibility, bands.exact);
    write_png(o.shadow_diff, view.width, view.height, 3, rgb.data(), overwrite);
  }
}

}  // namespace skyview::cli
