// skyview skymap: the directional exposure map of the sky over a period (direct and diffuse
// bands, Wh m-2 sr-1, Blinn–Newell longitude/latitude layout) plus a PNG preview.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <optional>

#include "command.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/core/version.h"
#include "skyview/raster/raster_io.h"
#include "skyview/sky/epw.h"
#include "skyview/sky/exposure_map.h"
#include "skyview/sky/exposure_preview.h"
#include "skyview/sky/exposure_steps.h"
#include "skyview/sky/sky_model.h"
#include "skyview/sky/sky_models.h"
#include "skyview/solar/time_parse.h"

namespace skyview::cli {
namespace {

// Hošek–Wilkie's spectral radiance is summed over its 11 bands only (docs/sky.md): its energies
// are about 40 % of the broadband ones, which a reader of the numbers must be told.
constexpr const char* kHosekSpectrum = "320-720 nm only (Hosek-Wilkie bands, not rescaled to broadband: about 40%)";

struct SkymapOptions {
  std::string output, preview, from, to, step = "30m", tz, sky = "preetham", epw;
  std::optional<double> lat, lon, elevation;
  double turbidity = 2.5, albedo = 0.2, efficacy = 125.0;
  int size = 512;
  bool no_preview = false;
  OutputOptions out;
  const CLI::App* app = nullptr;
};

std::unique_ptr<SkyModel> make_sky(const SkymapOptions& o) {
  if (o.sky == "preetham") return make_preetham_sky(o.turbidity, o.efficacy);
  if (o.sky == "hosek") return make_hosek_wilkie_sky(o.turbidity, o.albedo);
  if (o.sky == "perez-epw") return make_perez_all_weather_sky();
  if (o.sky == "isotropic") {
    if (!o.epw.empty()) return make_isotropic_sky();
    return make_isotropic_sky(std::shared_ptr<const SkyModel>(make_preetham_sky(o.turbidity, o.efficacy)));
  }
  throw UsageError("--sky must be preetham, hosek, perez-epw or isotropic (got '" + o.sky + "')");
}

int run(const SkymapOptions& o) {
  const auto started = std::chrono::steady_clock::now();
  const bool measured = o.sky == "perez-epw" || (o.sky == "isotropic" && !o.epw.empty());
  if (o.sky == "perez-epw" && o.epw.empty()) throw UsageError("--sky perez-epw needs --epw FILE");
  if (!o.epw.empty() && !measured) throw UsageError("--epw applies only to --sky perez-epw or isotropic");
  if (o.size < 8 || o.size > 8192) throw UsageError("--size must be within 8 .. 8192");
  if (o.from.empty() != o.to.empty()) throw UsageError("give both --from and --to, or neither");
  if (!measured && o.from.empty()) throw UsageError("--from and --to are required for --sky " + o.sky);
  const bool analytic_sun = o.sky == "preetham" || (o.sky == "isotropic" && !measured);
  refuse_unused(*o.app, "--step", !measured, "analytic skies (an EPW gives one step per hourly record)");
  refuse_unused(*o.app, "--turbidity", analytic_sun || o.sky == "hosek",
                "--sky preetham, hosek, or isotropic without --epw");
  refuse_unused(*o.app, "--albedo", o.sky == "hosek", "--sky hosek");
  refuse_unused(*o.app, "--luminous-efficacy", analytic_sun, "--sky preetham, or isotropic without --epw");
  refuse_unused(*o.app, "--preview", !o.no_preview, "runs without --no-preview");
  if (!o.preview.empty()) require_extension(o.preview, {".png"}, "--preview");
  const std::string preview =
      o.no_preview
          ? ""
          : (o.preview.empty() ? std::filesystem::path(o.output).replace_extension(".png").string() : o.preview);
  if (!preview.empty() && preview == o.output) throw Error("the preview would overwrite OUT; give --preview");
  const auto sky = make_sky(o);  // its options' errors before the outputs'
  check_outputs_apart({o.output, preview}, {o.epw});
  check_output_writable(o.output, o.out.overwrite);
  check_output_format(o.output, o.out.format, 2, o.out.creation_options);
  if (!preview.empty()) check_output_writable(preview, o.out.overwrite);

  std::optional<EpwFile> weather;
  if (!o.epw.empty()) weather = read_epw(o.epw);
  if (weather && weather->missing_solar_values > 0) {
    std::fprintf(stderr,
                 "Warning: %d irradiance values in '%s' are missing codes, not numbers, negative or above 1600 W/m2; "
                 "read as 0\n",
                 weather->missing_solar_values, o.epw.c_str());
  }
  // Even under -q: a whole-file total from a cut file looks like a year's and is not.
  if (weather && weather->declared_hours > 0 && weather->records.size() < std::size_t(weather->declared_hours)) {
    std::fprintf(stderr,
                 "Warning: '%s' holds %zu hourly records where its DATA PERIODS declares %d: it looks cut short, "
                 "and totals cover only the hours it holds\n",
                 o.epw.c_str(), weather->records.size(), weather->declared_hours);
  }
  Site site;
  if (!o.lat && !weather) throw UsageError("--lat and --lon are required");
  site.latitude_deg = o.lat ? *o.lat : weather->location.latitude_deg;
  site.longitude_deg = o.lon ? *o.lon : weather->location.longitude_deg;
  site.elevation_m = o.elevation ? *o.elevation : (weather ? weather->location.elevation_m : 0.0);
  if (!(std::abs(site.latitude_deg) <= 90.0)) throw UsageError("--lat must be within -90 .. 90");
  if (!(std::abs(site.longitude_deg) <= 180.0)) throw UsageError("--lon must be within -180 .. 180");
  if (o.lat.has_value() != o.lon.has_value()) throw UsageError("give both --lat and --lon, or neither (with --epw)");
  if (weather && o.lat && (*o.lat != weather->location.latitude_deg || *o.lon != weather->location.longitude_deg)) {
    std::fprintf(stderr, "Warning: the sun is placed for --lat %s --lon %s, not for the EPW's site (%s, %s)\n",
                 number_text(*o.lat).c_str(), number_text(*o.lon).c_str(),
                 number_text(weather->location.latitude_deg).c_str(),
                 number_text(weather->location.longitude_deg).c_str());
  }

  std::vector<ExposureStep> steps;
  std::map<std::string, std::string> meta;
  if (!o.tz.empty()) check_time_zone(o.tz);
  // The period's instants as parsed (local times resolved in --tz), recorded in UTC beside the text.
  std::optional<TimePeriod> period;
  if (!o.from.empty()) {
    period = TimePeriod{parse_time_option(o.from, o.tz).unix_utc, parse_time_option(o.to, o.tz).unix_utc};
    meta["FROM_UTC"] = format_iso_utc(period->from_utc);
    meta["TO_UTC"] = format_iso_utc(period->to_utc);
    if (!o.tz.empty()) meta["TIME_ZONE"] = o.tz;
  }
  if (weather) {
    steps = epw_steps(*weather, site, period);
    meta["EPW"] = o.epw;
    meta["EPW_MISSING_SOLAR_VALUES"] = std::to_string(weather->missing_solar_values);
    meta["EPW_STEPS"] = "one hour per record at its irradiance instant (--step is not used)";
  } else {
    const double step_s = parse_duration_option(o.step);
    // One step would stand for the whole period, its sun at the first instant (a day at 1d read 30.7
    // kWh/m2 where 1-minute steps give 11.0).
    if (period && step_s >= period->to_utc - period->from_utc) {
      throw UsageError("--step " + o.step + " is not shorter than the period from --from to --to; give a shorter step");
    }
    steps = regular_steps(site, period->from_utc, period->to_utc, step_s);
    meta["STEP"] = o.step;
  }
  ThreadLimit limit(o.out.threads);
  ExposureOptions eo;
  eo.width = eo.height = o.size;
  const ExposureMap map = integrate_exposure(*sky, steps, eo);

  const Direction up{0, 0, 1};
  const double direct_h = map.irradiation(ExposureBand::direct, up);
  const double diffuse_h = map.irradiation(ExposureBand::diffuse, up);
  meta["SKY"] = o.sky;
  meta["LATITUDE"] = number_text(site.latitude_deg);
  meta["LONGITUDE"] = number_text(site.longitude_deg);
  meta["ELEVATION"] = number_text(site.elevation_m);
  if (!o.from.empty()) {
    meta["FROM"] = o.from;
    meta["TO"] = o.to;
  }
  if (o.sky == "preetham" || o.sky == "hosek" || (o.sky == "isotropic" && !weather)) {
    meta["TURBIDITY"] = number_text(o.turbidity);
  }
  if (o.sky == "hosek") {
    meta["ALBEDO"] = number_text(o.albedo);
    meta["SPECTRUM"] = kHosekSpectrum;
  }
  if (o.sky == "preetham" || (o.sky == "isotropic" && !weather))
    meta["LUMINOUS_EFFICACY_LM_W"] = number_text(o.efficacy);
  meta["TIME_STEPS"] = std::to_string(steps.size());
  meta["PARAMETRISATION"] =
      "Blinn-Newell longitude/latitude: column x = azimuth [x,x+1)*360/width deg clockwise from north (N at the "
      "left edge, S in the middle); row y = zenith angle [y,y+1)*90/height deg (zenith at the top row)";
  meta["GLOBAL_HORIZONTAL_WH_M2"] = number_text(direct_h + diffuse_h);
  // No sky can deliver more than arrives at the top of the atmosphere; Preetham's can at high
  // turbidity (its diffuse part is a fitted distribution with no energy balance, docs/sky.md).
  double extraterrestrial_h = 0.0;
  for (const ExposureStep& s : steps) {
    extraterrestrial_h += extraterrestrial_normal_irradiance(s.conditions.day_of_year) *
                          std::max(0.0, std::cos(s.conditions.sun_zenith)) * s.hours;
  }
  meta["EXTRATERRESTRIAL_HORIZONTAL_WH_M2"] = number_text(extraterrestrial_h);
  if (direct_h + diffuse_h > extraterrestrial_h) {
    std::fprintf(stderr,
                 "Warning: the sky's global horizontal exposure, %.1f kWh/m2, exceeds the %.1f kWh/m2 outside the "
                 "atmosphere%s\n",
                 (direct_h + diffuse_h) / 1000, extraterrestrial_h / 1000,
                 analytic_sun ? " (Preetham's diffuse part has no energy balance; see docs/sky.md)" : "");
  }
  meta["DIRECT_HORIZONTAL_WH_M2"] = number_text(direct_h);
  meta["DIFFUSE_HORIZONTAL_WH_M2"] = number_text(diffuse_h);
  meta["SKYVIEW_VERSION"] = version();
  meta["SKYVIEW_COMMAND"] = command_line();

  WriteOptions wo;
  wo.format = o.out.format;
  wo.creation_options = o.out.creation_options;
  wo.overwrite = o.out.overwrite;
  wo.metadata = meta;
  GeoReference georef;  // x = azimuth (degrees), y = elevation (degrees); no CRS
  georef.geotransform = {0.0, 360.0 / o.size, 0.0, 90.0, 0.0, -90.0 / o.size};
  georef.has_geotransform = true;
  const std::string definition =
      "radiant exposure per unit solid angle; cosine-weighted integral over the "
      "sky a surface sees = its exposure (Wh/m2)";
  write_bands(o.output, o.size, o.size, georef,
              {{"direct",
                "Wh m-2 sr-1",
                map.band(ExposureBand::direct).data(),
                {{"DEFINITION", "sun disc splatted over its disc; " + definition}}},
               {"diffuse",
                "Wh m-2 sr-1",
                map.band(ExposureBand::diffuse).data(),
                {{"DEFINITION", "sky without the sun; " + definition}}}},
              wo);
  if (!preview.empty()) write_exposure_preview(preview, map, o.out.overwrite);
  if (!o.out.quiet) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    std::fprintf(stderr,
                 "skyview skymap: %zu steps, horizontal exposure %.1f kWh/m2 (direct %.1f, diffuse %.1f%s), %.2f s\n",
                 steps.size(), (direct_h + diffuse_h) / 1000, direct_h / 1000, diffuse_h / 1000,
                 o.sky == "hosek" ? "; 320-720 nm only" : "", seconds);
  }
  return 0;
}

Runner setup(CLI::App& app) {
  auto o = std::make_shared<SkymapOptions>();
  o->app = &app;
  app.add_option("OUT", o->output, "Output raster (bands direct, diffuse)")->required();
  app.add_option("--lat", o->lat, "Latitude, degrees north (default with --epw: the file's)");
  app.add_option("--lon", o->lon, "Longitude, degrees east (default with --epw: the file's)");
  app.add_option("--elevation", o->elevation, "Elevation above sea level, metres (for the sun position)");
  app.add_option("--from", o->from, "Start, ISO 8601 with offset or zone (perez-epw default: the whole file)");
  app.add_option("--to", o->to, "End (excluded)");
  app.add_option("--step", o->step, "Time step for analytic skies: 1h, 30m, 10min ...")->capture_default_str();
  app.add_option("--tz", o->tz, "IANA zone for --from/--to without an offset");
  app.add_option("--sky", o->sky, "preetham | hosek | perez-epw | isotropic")->capture_default_str();
  app.add_option("--turbidity", o->turbidity, "Atmospheric turbidity (preetham 2-10, hosek 1-10)")
      ->capture_default_str();
  app.add_option("--albedo", o->albedo, "Ground albedo for hosek, 0-1")->capture_default_str();
  app.add_option("--luminous-efficacy", o->efficacy, "lm/W turning Preetham luminance into radiance")
      ->capture_default_str();
  app.add_option("--epw", o->epw, "EnergyPlus weather file (perez-epw; isotropic from measured data)");
  app.add_option("--size", o->size, "Map width and height in cells")->capture_default_str();
  app.add_option("--preview", o->preview, "PNG preview path (default: OUT with .png)");
  app.add_flag("--no-preview", o->no_preview, "Do not write the PNG preview");
  add_output_options(app, o->out);
  app.footer(
      "Bands: 1 direct, 2 diffuse, radiant exposure per unit solid angle (Wh m-2 sr-1). Layout: columns = azimuth "
      "clockwise from north (N at the left edge, S in the middle), rows = zenith angle (zenith at the top, horizon "
      "at the bottom). See docs/sky.md.");
  return [o] { return run(*o); };
}

const Registration reg("skymap", "Directional exposure map of the sky over a period (sun and sky models, EPW data)",
                       setup);

}  // namespace
}  // namespace skyview::cli
