// skyview sun: where the sun is (NREL SPA) at one time or over a period, or the sunrise,
// transit and sunset of each day; optional façade shadow angles and tilted-surface incidence.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "command.h"
#include "skyview/core/error.h"
#include "skyview/solar/civil_time.h"
#include "skyview/solar/shadow_angles.h"
#include "skyview/solar/solar_position.h"
#include "skyview/solar/sun_events.h"
#include "skyview/solar/time_parse.h"

namespace skyview::cli {
namespace {

// At most this many rows, so that a typo in --step cannot fill the disk.
constexpr double kMaxRows = 1e7;

struct Options {
  std::string lat, lon, elevation = "0", pressure = "1013.25", temperature = "15", delta_t, delta_ut1 = "0";
  std::string time, from, to, step = "1h", tz, facade_azimuth, slope, surface_azimuth, convention = "local";
  bool csv = false, events = false;
  const CLI::App* app = nullptr;
};

// Numbers are read here rather than by CLI11 so that every bad value is one line naming the option.
double number(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v)) {
    throw UsageError(option + ": '" + text + "' is not a number");
  }
  return v;
}

std::optional<double> optional_number(const std::string& option, const std::string& text) {
  if (text.empty()) return std::nullopt;
  return number(option, text);
}

// How instants are shown in local time: an IANA zone, or the fixed offset the input carried.
struct LocalClock {
  std::string zone;
  double fixed_offset_s = 0.0;
  double offset_at(double unix_time) const { return zone.empty() ? fixed_offset_s : utc_offset_s(zone, unix_time); }
  std::string format(double unix_time) const { return format_iso_local(unix_time, offset_at(unix_time)); }
};

std::string fixed(double v, int decimals) {
  if (std::isnan(v)) return "";
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, v);
  return text;
}

struct Period {
  double first, last, step;
  LocalClock clock;
};

Period read_period(const Options& o) {
  if (!o.tz.empty()) check_time_zone(o.tz);
  const bool single = !o.time.empty();
  if (single == (!o.from.empty() || !o.to.empty())) throw UsageError("give either --time T or --from T1 --to T2");
  if (!single && (o.from.empty() || o.to.empty())) throw UsageError("--from and --to go together");
  const ParsedTime a = parse_time_option(single ? o.time : o.from, o.tz);
  const ParsedTime b = single || o.to == o.from ? a : parse_time_option(o.to, o.tz);
  // Events come a day at a time: --step is refused with them (and with --time), not read.
  const bool stepped = !single && !o.events;
  Period p{a.unix_utc, b.unix_utc, stepped ? parse_duration_option(o.step) : 86400.0, {}};
  if (p.last < p.first) throw UsageError("--to is before --from");
  if (stepped && (p.last - p.first) / p.step > kMaxRows)
    throw UsageError("--step " + o.step + " gives more than 1e7 rows");
  p.clock.zone = o.tz.empty() ? a.zone : o.tz;
  p.clock.fixed_offset_s = a.utc_offset_s;
  return p;
}

Site read_site(const Options& o) {
  Site s;
  if (o.lat.empty() || o.lon.empty()) throw UsageError("--lat and --lon are required");
  s.latitude_deg = number("--lat", o.lat);
  s.longitude_deg = number("--lon", o.lon);
  if (!(std::abs(s.latitude_deg) <= 90.0)) throw UsageError("--lat " + o.lat + " is outside -90..90 degrees");
  if (!(std::abs(s.longitude_deg) <= 180.0)) throw UsageError("--lon " + o.lon + " is outside -180..180 degrees");
  s.elevation_m = number("--elevation", o.elevation);
  s.pressure_mbar = number("--pressure", o.pressure);
  s.temperature_c = number("--temperature", o.temperature);
  if (auto dt = optional_number("--delta-t", o.delta_t)) {
    // Below -1e8 the library reads "automatic": a value the user gives is checked, not reinterpreted.
    if (!(std::abs(*dt) <= 1e6)) throw UsageError("--delta-t " + o.delta_t + " s is outside -1e6..1e6 s");
    s.delta_t_s = *dt;
  }
  s.delta_ut1_s = number("--delta-ut1", o.delta_ut1);
  validate_site(s);
  return s;
}

int print_positions(const Options& o, const Site& site, const Period& p) {
  const std::optional<double> facade = optional_number("--facade-azimuth", o.facade_azimuth);
  const std::optional<double> slope = optional_number("--slope", o.slope);
  if (slope && !(*slope >= 0.0 && *slope <= 180.0)) throw UsageError("--slope must be 0 to 180 degrees");
  if (!slope && !o.surface_azimuth.empty())
    throw UsageError("--surface-azimuth is the azimuth of --slope's surface: give --slope");
  const double surface_azimuth = optional_number("--surface-azimuth", o.surface_azimuth).value_or(180.0);
  if (o.csv) {
    std::printf(
        "time_utc,zenith_deg,azimuth_deg,elevation_deg,time_local,declination_deg,right_ascension_deg,"
        "earth_sun_distance_au,equation_of_time_min,delta_t_s%s%s\n",
        slope ? ",incidence_deg" : "", facade ? ",hsa_deg,vsa_deg,sun_on_facade" : "");
  } else {
    std::printf("# SPA (Reda & Andreas 2008): topocentric zenith with refraction, azimuth clockwise from north\n");
    std::printf("%-21s %-26s %10s %10s %10s %9s %8s %8s%s%s\n", "time_utc", "time_local", "zenith", "azimuth",
                "elevation", "decl", "eot_min", "dT_s", slope ? "  incidence" : "", facade ? "      hsa      vsa" : "");
  }
  const long rows = static_cast<long>(std::floor((p.last - p.first) / p.step + 1e-9)) + 1;
  // Zone offsets are looked up a chunk at a time: one switch of the C library's zone each.
  constexpr long kChunk = 4096;
  std::vector<double> times, offsets;
  for (long i = 0; i < rows; ++i) {
    const double t = p.first + static_cast<double>(i) * p.step;
    if (i % kChunk == 0) {
      times.clear();
      for (long j = i; j < std::min(rows, i + kChunk); ++j) times.push_back(p.first + static_cast<double>(j) * p.step);
      offsets = p.clock.zone.empty() ? std::vector<double>(times.size(), p.clock.fixed_offset_s)
                                     : utc_offsets_s(p.clock.zone, times);
    }
    const std::string local_time = format_iso_local(t, offsets[i % kChunk]);
    const SunPosition s = solar_position(t, site);
    std::string extra_csv, extra_text;
    if (slope) {
      const double incidence = incidence_angle_deg(s.zenith_deg, s.azimuth_deg, *slope, surface_azimuth);
      extra_csv += "," + fixed(incidence, 5);
      extra_text +=
          " " + std::string(10 - std::min<std::size_t>(10, fixed(incidence, 5).size()), ' ') + fixed(incidence, 5);
    }
    if (facade) {
      const ShadowAngles a = shadow_angles(s.azimuth_deg, s.elevation_deg, *facade);
      extra_csv +=
          "," + fixed(a.horizontal_deg, 5) + "," + fixed(a.vertical_deg, 5) + "," + (a.sun_on_facade ? "1" : "0");
      char text[64];
      std::snprintf(text, sizeof text, " %8.3f %8s", a.horizontal_deg,
                    a.sun_on_facade ? fixed(a.vertical_deg, 3).c_str() : "-");
      extra_text += text;
    }
    if (o.csv) {
      std::printf("%s,%.6f,%.6f,%.6f,%s,%.6f,%.6f,%.8f,%.4f,%.2f%s\n", format_iso_utc(t).c_str(), s.zenith_deg,
                  s.azimuth_deg, s.elevation_deg, local_time.c_str(), s.declination_deg, s.right_ascension_deg,
                  s.earth_sun_distance_au, s.equation_of_time_min, s.delta_t_s, extra_csv.c_str());
    } else {
      std::printf("%-21s %-26s %10.5f %10.5f %10.5f %9.4f %8.3f %8.2f%s\n", format_iso_utc(t).c_str(),
                  local_time.c_str(), s.zenith_deg, s.azimuth_deg, s.elevation_deg, s.declination_deg,
                  s.equation_of_time_min, s.delta_t_s, extra_text.c_str());
    }
  }
  return 0;
}

const char* kind_name(DayKind k) {
  switch (k) {
    case DayKind::polar_day:
      return "polar_day";
    case DayKind::polar_night:
      return "polar_night";
    case DayKind::no_sunset:
      return "no_sunset";
    case DayKind::no_sunrise:
      return "no_sunrise";
    default:
      return "normal";
  }
}

int print_events(const Options& o, const Site& site, const Period& p) {
  if (o.convention != "local" && o.convention != "spa") throw UsageError("--convention must be local or spa");
  const SunEventDay convention = o.convention == "spa" ? SunEventDay::spa_utc_day : SunEventDay::local_day;
  const auto local_day = [&](double t) {
    return static_cast<std::int64_t>(std::floor((t + p.clock.offset_at(t)) / 86400.0));
  };
  const std::int64_t first = local_day(p.first), last = local_day(p.last);
  if (last - first > 400000) throw UsageError("--events covers more than 400000 days");
  // The first and last days first: their events reach half a day beyond them, and a date outside
  // the SPA's years must fail before a line is printed.
  for (const auto& [day, t] : {std::pair{first, p.first}, std::pair{last, p.last}}) {
    try {
      sun_events(civil_from_days(day), p.clock.offset_at(t), site, convention);
    } catch (const Error& e) {
      if (convention != SunEventDay::local_day) throw;
      throw Error(std::string(e.what()) + ": a local day's events need the sun half a day either side of its transit");
    }
  }
  if (o.csv) {
    std::printf(
        "date,sunrise_utc,transit_utc,sunset_utc,sunrise_local,transit_local,sunset_local,day_length_h,"
        "transit_elevation_deg,day_kind\n");
  } else {
    std::printf("# SPA Appendix A.2; sun centre at %.5f deg altitude; %s\n", kSunriseAltitudeDeg,
                convention == SunEventDay::local_day ? "events of the local calendar day"
                                                     : "SPA convention: events wrapped into the UT day of that date");
    std::printf("%-11s %-26s %-26s %-26s %9s %9s %s\n", "date", "sunrise", "transit", "sunset", "day_h", "noon_elev",
                "kind");
  }
  for (std::int64_t day = first; day <= last; ++day) {
    const CivilDate date = civil_from_days(day);
    // The clock offset at local noon decides the day's offset (DST changes happen at night).
    const double noon_guess = static_cast<double>(day) * 86400.0 + 43200.0;
    const double offset = p.clock.offset_at(noon_guess - p.clock.offset_at(noon_guess));
    // A date the zone skipped (Samoa went from 29 to 31 December 2011) has no events of its own:
    // its noon would be the next day's.
    if (local_day(static_cast<double>(day) * 86400.0 + 43200.0 - offset) != day) continue;
    const SunEvents e = sun_events(date, offset, site, convention);
    std::string date_text = format_iso_utc(static_cast<double>(day) * 86400.0);
    date_text.resize(date_text.find('T'));
    auto utc = [](const std::optional<double>& t) { return t ? format_iso_utc(*t) : std::string(); };
    auto local = [&](const std::optional<double>& t) { return t ? p.clock.format(*t) : std::string(); };
    if (o.csv) {
      std::printf("%s,%s,%s,%s,%s,%s,%s,%.4f,%.4f,%s\n", date_text.c_str(), utc(e.sunrise_utc).c_str(),
                  utc(e.transit_utc).c_str(), utc(e.sunset_utc).c_str(), local(e.sunrise_utc).c_str(),
                  local(e.transit_utc).c_str(), local(e.sunset_utc).c_str(), e.day_length_h(), e.transit_elevation_deg,
                  kind_name(e.kind));
    } else {
      std::printf("%-11s %-26s %-26s %-26s %9.4f %9.4f %s\n", date_text.c_str(),
                  e.sunrise_utc ? local(e.sunrise_utc).c_str() : "-", local(e.transit_utc).c_str(),
                  e.sunset_utc ? local(e.sunset_utc).c_str() : "-", e.day_length_h(), e.transit_elevation_deg,
                  kind_name(e.kind));
    }
  }
  return 0;
}

Runner setup(CLI::App& app) {
  auto o = std::make_shared<Options>();
  app.add_option("--lat", o->lat, "Latitude, degrees north (required)")->type_name("DEG");
  app.add_option("--lon", o->lon, "Longitude, degrees east (required)")->type_name("DEG");
  app.add_option("--elevation", o->elevation, "Elevation above sea level, metres")
      ->capture_default_str()
      ->type_name("M");
  app.add_option("--pressure", o->pressure, "Annual mean air pressure, mbar (0 = no refraction)")
      ->capture_default_str()
      ->type_name("MBAR");
  app.add_option("--temperature", o->temperature, "Annual mean temperature, degrees C")
      ->capture_default_str()
      ->type_name("C");
  app.add_option("--delta-t", o->delta_t,
                 "TT - UT1 in seconds (default: automatic, observed 1950-2020, 69.2 s to 2050, "
                 "Espenak-Meeus outside)")
      ->type_name("S");
  app.add_option("--delta-ut1", o->delta_ut1, "UT1 - UTC in seconds (-1..1)")->capture_default_str()->type_name("S");
  app.add_option("--time", o->time,
                 "One instant: ISO 8601 with offset or zone, e.g. 2003-10-17T12:30:30-07:00 or "
                 "'2024-06-21T12:00 Europe/Athens'")
      ->type_name("T");
  app.add_option("--from", o->from, "Start of a period (same forms as --time)")->type_name("T1");
  app.add_option("--to", o->to, "End of the period, included")->type_name("T2");
  app.add_option("--step", o->step, "Step of the period: 1h, 30m, 15min, 10s, 1d")
      ->capture_default_str()
      ->type_name("DURATION");
  app.add_option("--tz", o->tz, "IANA zone for times without an offset and for local output, e.g. Europe/Athens")
      ->type_name("ZONE");
  app.add_flag("--csv", o->csv, "CSV: time_utc,zenith_deg,azimuth_deg,elevation_deg, then the other columns");
  app.add_flag("--events", o->events, "Sunrise, transit and sunset of each local day instead of positions");
  app.add_option("--convention", o->convention,
                 "Events day: 'local' (events of the local calendar day) or 'spa' (SPA's UT-day wrapping, as in "
                 "the report's test output)")
      ->capture_default_str()
      ->check(CLI::IsMember({"local", "spa"}))
      ->type_name("local|spa");
  app.add_option("--facade-azimuth", o->facade_azimuth,
                 "Add horizontal/vertical shadow angles (HSA, VSA) for a façade facing this azimuth (deg from north)")
      ->type_name("DEG");
  app.add_option("--slope", o->slope, "Add the incidence angle on a surface tilted this many degrees")
      ->type_name("DEG");
  app.add_option("--surface-azimuth", o->surface_azimuth,
                 "Azimuth the tilted surface faces, degrees clockwise from north (default 180)")
      ->type_name("DEG");
  o->app = &app;
  return [o] {
    const CLI::App& a = *o->app;
    const std::string positions = "sun positions (not --events)";
    for (const char* option : {"--facade-azimuth", "--slope", "--surface-azimuth"})
      refuse_unused(a, option, !o->events, positions);
    refuse_unused(a, "--step", !o->events && o->time.empty(), "a period of positions (--from and --to, no --events)");
    refuse_unused(a, "--convention", o->events, "--events");
    const Site site = read_site(*o);
    const Period period = read_period(*o);
    // Every instant the run will compute is in the SPA's range before a line is printed: the range
    // is one span, so its ends decide (a half-written CSV with exit 1 is worse than none).
    if (!o->events) {
      for (const double t : {period.first, period.last}) solar_position(t, site);
    }
    return o->events ? print_events(*o, site, period) : print_positions(*o, site, period);
  };
}

const Registration reg("sun", "Sun position (NREL SPA), sunrise/transit/sunset and façade shadow angles", setup);

}  // namespace
}  // namespace skyview::cli
