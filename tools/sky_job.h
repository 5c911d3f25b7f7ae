#pragma once
// The sky options `skyview skymap` and `skyview exposure` share (the sky model and its parameters,
// the site, the period and its steps, a weather file), and what the commands do with them before
// the library builds the sky (sky_request.h).
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "command.h"
#include "skyview/raster/raster_site.h"
#include "skyview/raster/terrain.h"
#include "skyview/sky/sky_request.h"
#include "skyview/solar/solar_position.h"

namespace skyview::cli {

// --lat, --lon, --elevation, --from, --to, --step, --tz, --sky, --turbidity,
// --luminous-efficacy, --epw into `request`. `site_default` says where --lat/--lon default to
// ("default with --epw: the file's").
void add_sky_options(CLI::App& app, SkyRequest& request, const std::string& site_default);

// Refuses what the request's sky would not use (--step with an EPW, --turbidity with perez-epw,
// --luminous-efficacy beyond Preetham's energy) and options that do not go together.
void check_sky_options(const CLI::App& app, const SkyRequest& request);

// Where the sun is seen from for a raster: --lat/--lon where given (both), else the raster's centre
// (from its CRS); the elevation from --elevation, else the raster's height at its centre. Throws,
// naming `input`, where the raster has no CRS and no --lat/--lon are given. `source` says which.
Site raster_sun_site(const Terrain& terrain, const std::string& input, const std::optional<double>& lat,
                     const std::optional<double>& lon, const std::optional<double>& elevation, std::string& source);

// The same for any place: `centre` from its CRS (nullopt: none, then --lat/--lon are needed, the
// error naming `what`), `ground` its height above sea level (m) for the default --elevation, and
// `where` what `source` calls the centre ("the scene's centre").
Site sun_site(const std::optional<GeoPoint>& centre, double ground, const std::string& what, const std::string& where,
              const std::optional<double>& lat, const std::optional<double>& lon,
              const std::optional<double>& elevation, std::string& source);

// Throws skyview::Error naming the sun's elevation, the instant and the site unless the sun's
// centre is above the horizon: there are no shadows to cast.
void require_sun_up(const SunPosition& sun, double unix_utc, const Site& site);

// The metadata of one instant's sun (TIME, TIME_UTC, TIME_ZONE, LATITUDE, LONGITUDE, SITE_SOURCE,
// SUN_AZIMUTH_DEG, SUN_ELEVATION_DEG, SUN_POSITION) that skyview shadow and render --time share.
void add_sun_instant_metadata(std::map<std::string, std::string>& m, const std::string& time_text,
                              const std::string& zone, double unix_utc, const Site& site,
                              const std::string& site_source, const SunPosition& sun);

// "Warning: ..." on stderr for each, even under -q: they change what the numbers mean.
void print_warnings(const std::vector<std::string>& warnings);

}  // namespace skyview::cli
