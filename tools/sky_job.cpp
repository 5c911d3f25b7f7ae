#include "sky_job.h"

#include <cmath>
#include <cstdio>
#include <set>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/raster/raster_site.h"
#include "skyview/solar/civil_time.h"

namespace skyview::cli {

void add_sky_options(CLI::App& app, SkyRequest& r, const std::string& site_default) {
  app.add_option("--lat", r.latitude, "Latitude, degrees north (" + site_default + ")");
  app.add_option("--lon", r.longitude, "Longitude, degrees east (" + site_default + ")");
  app.add_option("--elevation", r.elevation, "Elevation above sea level, metres (for the sun position)");
  app.add_option("--from", r.from, "Start, ISO 8601 with offset or zone (perez-epw default: the whole file)");
  app.add_option("--to", r.to, "End (excluded)");
  app.add_option("--step", r.step, "Time step for analytic skies: 1h, 30m, 10min ...")->capture_default_str();
  app.add_option("--tz", r.tz, "IANA zone for --from/--to without an offset");
  app.add_option("--sky", r.sky, "preetham | hosek | perez-epw | isotropic")->capture_default_str();
  app.add_option("--turbidity", r.turbidity, "Atmospheric turbidity (preetham 2-10, hosek 1-10)")
      ->capture_default_str();
  app.add_option("--luminous-efficacy", r.luminous_efficacy, "lm/W turning Preetham luminance into radiance")
      ->capture_default_str();
  app.add_option("--epw", r.epw, "EnergyPlus weather file (perez-epw; isotropic from measured data)");
}

void check_sky_options(const CLI::App& app, const SkyRequest& r) {
  check_sky_request(r);
  std::set<std::string> given;
  for (const std::string& name : sky_option_names()) {
    if (app.count(name) > 0) given.insert(name);
  }
  check_sky_options_used(r, given);
}

Site sun_site(const std::optional<GeoPoint>& centre, double ground, const std::string& what, const std::string& where,
              const std::optional<double>& lat, const std::optional<double>& lon,
              const std::optional<double>& elevation, std::string& source) {
  if (lat.has_value() != lon.has_value()) throw UsageError("give both --lat and --lon, or neither (" + where + ")");
  Site site;
  if (lat) {
    site.latitude_deg = *lat;
    site.longitude_deg = *lon;
    source = "--lat/--lon";
  } else {
    if (!centre) throw Error(what + " has no CRS to place the sun: give --lat and --lon");
    site.latitude_deg = centre->latitude_deg;
    site.longitude_deg = centre->longitude_deg;
    source = where;
  }
  if (!(std::abs(site.latitude_deg) <= 90.0)) throw UsageError("--lat must be within -90 .. 90");
  if (!(std::abs(site.longitude_deg) <= 180.0)) throw UsageError("--lon must be within -180 .. 180");
  site.elevation_m = elevation ? *elevation : ground;
  return site;
}

Site raster_sun_site(const Terrain& t, const std::string& input, const std::optional<double>& lat,
                     const std::optional<double>& lon, const std::optional<double>& elevation, std::string& source) {
  // The centre only when it is needed: a raster without CRS may still be placed by --lat/--lon.
  const std::optional<GeoPoint> centre =
      lat || lon ? std::nullopt : raster_centre_geographic(t.georef, t.width(), t.height());
  const double mid = t.heights(t.width() / 2, t.height() / 2);
  return sun_site(centre, t.base_height + (std::isnan(mid) ? 0.0 : mid), "'" + input + "'", "the raster's centre", lat,
                  lon, elevation, source);
}

void require_sun_up(const SunPosition& sun, double unix_utc, const Site& site) {
  if (sun.elevation_deg > 0.0) return;
  throw Error("the sun's centre is " + number_text(std::round(-sun.elevation_deg * 100) / 100) +
              " degrees below the horizon at " + format_iso_utc(unix_utc) + " at " + number_text(site.latitude_deg) +
              ", " + number_text(site.longitude_deg) + ": no shadows to cast");
}

void print_warnings(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) std::fprintf(stderr, "Warning: %s\n", w.c_str());
}

void add_sun_instant_metadata(std::map<std::string, std::string>& m, const std::string& time_text,
                              const std::string& zone, double unix_utc, const Site& site,
                              const std::string& site_source, const SunPosition& sun) {
  m["TIME"] = time_text;
  m["TIME_UTC"] = format_iso_utc(unix_utc);
  if (!zone.empty()) m["TIME_ZONE"] = zone;
  m["LATITUDE"] = number_text(site.latitude_deg);
  m["LONGITUDE"] = number_text(site.longitude_deg);
  m["SITE_SOURCE"] = site_source;
  m["SUN_AZIMUTH_DEG"] = number_text(sun.azimuth_deg);
  m["SUN_ELEVATION_DEG"] = number_text(sun.elevation_deg);
  m["SUN_POSITION"] = "NREL SPA, topocentric, refracted (15 C, 1013.25 mbar)";
}

}  // namespace skyview::cli
