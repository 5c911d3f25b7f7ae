// From the sky options to a model, a site and time steps, and from those to the exposure map.
#include "skyview/sky/sky_request.h"

#include <algorithm>
#include <cmath>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/sky/sky_models.h"
#include "skyview/solar/time_parse.h"

namespace skyview {

// Hošek–Wilkie's spectral radiance is summed over its 11 bands only (docs/sky.md): its energies
// are about 40 % of the broadband ones, which a reader of the numbers must be told.
const char* const kHosekSpectrum = "320-720 nm only (Hosek-Wilkie bands, not rescaled to broadband: about 40%)";

const std::vector<std::string>& sky_option_names() {
  static const std::vector<std::string> names{"--lat",  "--lon", "--elevation", "--from",      "--to",
                                              "--step", "--tz",  "--sky",       "--turbidity", "--luminous-efficacy",
                                              "--epw"};
  return names;
}

bool measured_sky(const SkyRequest& r) { return r.sky == "perez-epw" || (r.sky == "isotropic" && !r.epw.empty()); }

bool preetham_energy(const SkyRequest& r) { return r.sky == "preetham" || (r.sky == "isotropic" && r.epw.empty()); }

std::unique_ptr<SkyModel> make_sky_model(const SkyRequest& r) {
  if (r.sky == "preetham") return make_preetham_sky(r.turbidity, r.luminous_efficacy);
  if (r.sky == "hosek") return make_hosek_wilkie_sky(r.turbidity, r.albedo);
  if (r.sky == "perez-epw") return make_perez_all_weather_sky();
  if (r.sky == "isotropic") {
    if (!r.epw.empty()) return make_isotropic_sky();
    return make_isotropic_sky(std::shared_ptr<const SkyModel>(make_preetham_sky(r.turbidity, r.luminous_efficacy)));
  }
  throw UsageError("--sky must be preetham, hosek, perez-epw or isotropic (got '" + r.sky + "')");
}

void check_sky_request(const SkyRequest& r) {
  if (r.sky == "perez-epw" && r.epw.empty()) throw UsageError("--sky perez-epw needs --epw FILE");
  if (!r.epw.empty() && !measured_sky(r)) throw UsageError("--epw applies only to --sky perez-epw or isotropic");
  if (r.from.empty() != r.to.empty()) throw UsageError("give both --from and --to, or neither");
  if (!measured_sky(r) && r.from.empty()) throw UsageError("--from and --to are required for --sky " + r.sky);
}

void check_sky_options_used(const SkyRequest& r, const std::set<std::string>& given) {
  auto refuse_unused = [&](const std::string& option, bool used, const std::string& where) {
    if (!used && given.count(option) > 0) throw UsageError(option + " applies only to " + where);
  };
  refuse_unused("--step", !measured_sky(r), "analytic skies (an EPW gives one step per hourly record)");
  refuse_unused("--turbidity", preetham_energy(r) || r.sky == "hosek",
                "--sky preetham, hosek, or isotropic without --epw");
  refuse_unused("--luminous-efficacy", preetham_energy(r), "--sky preetham, or isotropic without --epw");
}

namespace {

ParsedTime parse_noting_ambiguity(const std::string& text, const std::string& zone,
                                  std::vector<std::string>& warnings) {
  const ParsedTime t = as_usage_error([&] { return parse_time(text, zone); });
  if (t.ambiguous) {
    warnings.push_back("'" + text + "' occurs twice in " + t.zone + " (clocks set back); taken as the earlier, " +
                       format_iso_local(t.unix_utc, t.utc_offset_s) + "; give a UTC offset to choose");
  }
  return t;
}

}  // namespace

PreparedSky prepare_sky(const SkyRequest& r, const std::optional<Site>& default_site) {
  check_sky_request(r);
  PreparedSky out;
  out.model = make_sky_model(r);
  if (!r.epw.empty()) {
    out.weather = read_epw(r.epw);
    const EpwFile& w = *out.weather;
    if (w.missing_solar_values > 0) {
      out.warnings.push_back(std::to_string(w.missing_solar_values) + " irradiance values in '" + r.epw +
                             "' are missing codes, not numbers, negative or above 1600 W/m2; read as 0");
    }
    // A whole-file total from a cut file looks like a year's and is not.
    if (w.declared_hours > 0 && w.records.size() < std::size_t(w.declared_hours)) {
      out.warnings.push_back("'" + r.epw + "' holds " + std::to_string(w.records.size()) +
                             " hourly records where its DATA PERIODS declares " + std::to_string(w.declared_hours) +
                             ": it looks cut short, and totals cover only the hours it holds");
    }
  }
  const std::optional<EpwFile>& weather = out.weather;
  if (r.latitude.has_value() != r.longitude.has_value()) {
    throw Error(std::string("give both --lat and --lon, or neither") + (weather        ? " (with --epw)"
                                                                        : default_site ? " (the raster's centre)"
                                                                                       : ""));
  }
  if (!r.latitude && !weather && !default_site) throw UsageError("--lat and --lon are required");
  Site& site = out.site;
  if (r.latitude) {
    site.latitude_deg = *r.latitude;
    site.longitude_deg = *r.longitude;
  } else if (default_site) {
    site.latitude_deg = default_site->latitude_deg;
    site.longitude_deg = default_site->longitude_deg;
  } else {
    site.latitude_deg = weather->location.latitude_deg;
    site.longitude_deg = weather->location.longitude_deg;
  }
  site.elevation_m = r.elevation    ? *r.elevation
                     : default_site ? default_site->elevation_m
                     : weather      ? weather->location.elevation_m
                                    : 0.0;
  if (!(std::abs(site.latitude_deg) <= 90.0)) throw UsageError("--lat must be within -90 .. 90");
  if (!(std::abs(site.longitude_deg) <= 180.0)) throw UsageError("--lon must be within -180 .. 180");
  if (weather && r.latitude &&
      (*r.latitude != weather->location.latitude_deg || *r.longitude != weather->location.longitude_deg)) {
    out.warnings.push_back("the sun is placed for --lat " + number_text(*r.latitude) + " --lon " +
                           number_text(*r.longitude) + ", not for the EPW's site (" +
                           number_text(weather->location.latitude_deg) + ", " +
                           number_text(weather->location.longitude_deg) + ")");
  }

  auto& meta = out.metadata;
  if (!r.tz.empty()) check_time_zone(r.tz);
  // The period's instants as parsed (local times resolved in --tz), recorded in UTC beside the text.
  if (!r.from.empty()) {
    out.period = TimePeriod{parse_noting_ambiguity(r.from, r.tz, out.warnings).unix_utc,
                            parse_noting_ambiguity(r.to, r.tz, out.warnings).unix_utc};
    if (!(out.period->to_utc > out.period->from_utc))
      throw Error("the period is empty: --to must be later than --from");
    meta["FROM"] = r.from;
    meta["TO"] = r.to;
    meta["FROM_UTC"] = format_iso_utc(out.period->from_utc);
    meta["TO_UTC"] = format_iso_utc(out.period->to_utc);
    if (!r.tz.empty()) meta["TIME_ZONE"] = r.tz;
  }
  if (weather) {
    out.steps = epw_steps(*weather, site, out.period);
    meta["EPW"] = r.epw;
    meta["EPW_MISSING_SOLAR_VALUES"] = std::to_string(weather->missing_solar_values);
    meta["EPW_STEPS"] = "one hour per record at its irradiance instant (--step is not used)";
  } else {
    const double step_s = as_usage_error([&] { return parse_duration_s(r.step); });
    // One step would stand for the whole period, its sun at the first instant (a day at 1d read 30.7
    // kWh/m2 where 1-minute steps give 11.0).
    if (step_s >= out.period->to_utc - out.period->from_utc) {
      throw UsageError("--step " + r.step + " is not shorter than the period from --from to --to; give a shorter step");
    }
    out.steps = regular_steps(site, out.period->from_utc, out.period->to_utc, step_s);
    meta["STEP"] = r.step;
  }
  meta["SKY"] = r.sky;
  meta["LATITUDE"] = number_text(site.latitude_deg);
  meta["LONGITUDE"] = number_text(site.longitude_deg);
  meta["ELEVATION"] = number_text(site.elevation_m);
  if (r.sky == "preetham" || r.sky == "hosek" || preetham_energy(r)) meta["TURBIDITY"] = number_text(r.turbidity);
  if (r.sky == "hosek") {
    meta["ALBEDO"] = number_text(r.albedo);
    meta["SPECTRUM"] = kHosekSpectrum;
  }
  if (preetham_energy(r)) meta["LUMINOUS_EFFICACY_LM_W"] = number_text(r.luminous_efficacy);
  meta["TIME_STEPS"] = std::to_string(out.steps.size());
  return out;
}

ExposureMap make_exposure_map(PreparedSky& sky, int size) {
  ExposureOptions eo;
  eo.width = eo.height = size;
  ExposureMap map = integrate_exposure(*sky.model, sky.steps, eo);
  const Direction up{0, 0, 1};
  const double direct_h = map.irradiation(ExposureBand::direct, up);
  const double diffuse_h = map.irradiation(ExposureBand::diffuse, up);
  auto& meta = sky.metadata;
  meta["PARAMETRISATION"] =
      "Blinn-Newell longitude/latitude: column x = azimuth [x,x+1)*360/width deg clockwise from north (N at the "
      "left edge, S in the middle); row y = zenith angle [y,y+1)*90/height deg (zenith at the top row)";
  meta["GLOBAL_HORIZONTAL_WH_M2"] = number_text(direct_h + diffuse_h);
  meta["DIRECT_HORIZONTAL_WH_M2"] = number_text(direct_h);
  meta["DIFFUSE_HORIZONTAL_WH_M2"] = number_text(diffuse_h);
  // No sky can deliver more than arrives at the top of the atmosphere; Preetham's can at high
  // turbidity (its diffuse part is a fitted distribution with no energy balance, docs/sky.md).
  double extraterrestrial_h = 0.0;
  for (const ExposureStep& s : sky.steps) {
    extraterrestrial_h += extraterrestrial_normal_irradiance(s.conditions.day_of_year) *
                          std::max(0.0, std::cos(s.conditions.sun_zenith)) * s.hours;
  }
  meta["EXTRATERRESTRIAL_HORIZONTAL_WH_M2"] = number_text(extraterrestrial_h);
  if (direct_h + diffuse_h > extraterrestrial_h) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "the sky's global horizontal exposure, %.1f kWh/m2, exceeds the %.1f kWh/m2 outside the "
                  "atmosphere",
                  (direct_h + diffuse_h) / 1000, extraterrestrial_h / 1000);
    const bool preetham = meta.count("LUMINOUS_EFFICACY_LM_W") > 0;
    sky.warnings.push_back(std::string(text) +
                           (preetham ? " (Preetham's diffuse part has no energy balance; see docs/sky.md)" : ""));
  }
  return map;
}

}  // namespace skyview
