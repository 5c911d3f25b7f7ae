#pragma once
// A sky over a period as the commands ask for it (skyview skymap, skyview exposure and the Python
// module share these options): the model and its parameters, the site, and the period with its
// steps or the hours of a weather file. prepare_sky turns a request into the model and the time
// steps; make_exposure_map integrates them into the directional exposure map and records what a
// reader of the map needs in its metadata. docs/sky.md describes the options.
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "skyview/sky/epw.h"
#include "skyview/sky/exposure_map.h"
#include "skyview/sky/exposure_steps.h"
#include "skyview/sky/sky_model.h"
#include "skyview/solar/solar_position.h"

namespace skyview {

struct SkyRequest {
  std::string sky = "preetham";  // preetham | hosek | perez-epw | isotropic
  double turbidity = 2.5;
  double albedo = 0.2;  // the ground albedo of Hošek–Wilkie's sky
  double luminous_efficacy = 125.0;
  std::string epw;  // a weather file: perez-epw, or isotropic from measured data
  std::optional<double> latitude, longitude, elevation;
  std::string from, to, tz;  // ISO 8601 as given; tz names the zone of times without an offset
  std::string step = "30m";  // analytic skies
};

// The sky options' long names on the command line (--lat, --lon, --elevation, --from, --to,
// --step, --tz, --sky, --turbidity, --luminous-efficacy, --epw), for runs that refuse them all (a
// sky read from a map file).
const std::vector<std::string>& sky_option_names();

// Whether the request's sky reads measured irradiances (perez-epw, or isotropic with --epw).
bool measured_sky(const SkyRequest& request);
// Whether its sun and diffuse energy come from Preetham's clear sky (preetham, isotropic without --epw).
bool preetham_energy(const SkyRequest& request);

// The sky model a request names. Throws skyview::Error for an unknown name or bad parameters.
std::unique_ptr<SkyModel> make_sky_model(const SkyRequest& request);

// Throws skyview::Error, one line, where the request's options do not go together (an EPW sky
// without a file, a file for an analytic sky, a period half given or missing for an analytic sky).
void check_sky_request(const SkyRequest& request);

// Throws skyview::UsageError for an option in `given` (the command line's long names: "--step")
// that the request's sky would not use: --step with an EPW, --turbidity beyond Preetham and
// Hošek–Wilkie, --luminous-efficacy beyond Preetham's energy. A batch job would otherwise get the
// answer to another question than it asked, without a word.
void check_sky_options_used(const SkyRequest& request, const std::set<std::string>& given);

struct PreparedSky {
  Site site;
  std::shared_ptr<const SkyModel> model;
  std::vector<ExposureStep> steps;
  std::optional<EpwFile> weather;
  std::optional<TimePeriod> period;  // of --from/--to, in UTC
  // SKY, LATITUDE, LONGITUDE, ELEVATION, FROM/TO (as given), FROM_UTC/TO_UTC, TIME_ZONE, STEP or
  // EPW and EPW_STEPS, TURBIDITY, ALBEDO, LUMINOUS_EFFICACY_LM_W, SPECTRUM, TIME_STEPS.
  std::map<std::string, std::string> metadata;
  // What a user must be told even under -q (missing EPW values, a file cut short, a site moved
  // from the EPW's, an ambiguous local time).
  std::vector<std::string> warnings;
};

// Checks the request, reads its weather file, places the site and makes the time steps. The site
// is --lat/--lon where given, else `default_site` (a raster's centre) where given, else the EPW's;
// the elevation likewise. Throws skyview::Error (one line) for bad input.
PreparedSky prepare_sky(const SkyRequest& request, const std::optional<Site>& default_site = std::nullopt);

// Integrates the prepared sky into a size × size map, and adds to its metadata the horizontal
// totals (GLOBAL/DIRECT/DIFFUSE_HORIZONTAL_WH_M2), the extraterrestrial horizontal exposure and the
// parametrisation; warns (in `sky.warnings`) where the sky delivers more than arrives outside the
// atmosphere.
ExposureMap make_exposure_map(PreparedSky& sky, int size);

// Hošek–Wilkie's energies cover its bands only: what outputs of such a sky say in SPECTRUM.
extern const char* const kHosekSpectrum;

}  // namespace skyview
