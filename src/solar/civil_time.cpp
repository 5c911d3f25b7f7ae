// Proleptic Gregorian calendar arithmetic over 400-year cycles (146097 days), so negative
// years and years past 9999 need no special cases.
#include "skyview/solar/civil_time.h"

#include <cmath>
#include <cstdio>

namespace skyview {

namespace {

constexpr std::int64_t kDaysPer400Years = 146097;
// Days from 0000-03-01 to 1970-01-01: the cycle arithmetic counts from a March 1 so that
// the leap day falls at the end of the counted year.
constexpr std::int64_t kMarch1Year0ToEpoch = 719468;

std::int64_t floor_div(std::int64_t a, std::int64_t b) { return a / b - ((a % b != 0) && ((a < 0) != (b < 0))); }

}  // namespace

std::int64_t days_from_civil(const CivilDate& d) {
  const std::int64_t y = static_cast<std::int64_t>(d.year) - (d.month <= 2 ? 1 : 0);
  const std::int64_t era = floor_div(y, 400);
  const std::int64_t year_of_era = y - era * 400;                                 // [0, 399]
  const std::int64_t month_from_march = (d.month + 9) % 12;                       // March = 0
  const std::int64_t day_of_year = (153 * month_from_march + 2) / 5 + d.day - 1;  // [0, 365]
  const std::int64_t day_of_era = year_of_era * 365 + year_of_era / 4 - year_of_era / 100 + day_of_year;
  return era * kDaysPer400Years + day_of_era - kMarch1Year0ToEpoch;
}

CivilDate civil_from_days(std::int64_t days) {
  const std::int64_t z = days + kMarch1Year0ToEpoch;
  const std::int64_t era = floor_div(z, kDaysPer400Years);
  const std::int64_t day_of_era = z - era * kDaysPer400Years;  // [0, 146096]
  const std::int64_t year_of_era =
      (day_of_era - day_of_era / 1460 + day_of_era / 36524 - day_of_era / 146096) / 365;  // [0, 399]
  const std::int64_t day_of_year = day_of_era - (365 * year_of_era + year_of_era / 4 - year_of_era / 100);
  const std::int64_t month_from_march = (5 * day_of_year + 2) / 153;
  CivilDate d;
  d.day = static_cast<int>(day_of_year - (153 * month_from_march + 2) / 5 + 1);
  d.month = static_cast<int>(month_from_march < 10 ? month_from_march + 3 : month_from_march - 9);
  d.year = static_cast<int>(year_of_era + era * 400 + (d.month <= 2 ? 1 : 0));
  return d;
}

double seconds_from_civil(const CivilDateTime& t) {
  return static_cast<double>(days_from_civil(t.date)) * 86400.0 + t.hour * 3600.0 + t.minute * 60.0 + t.second;
}

CivilDateTime civil_from_seconds(double seconds) {
  const double days = std::floor(seconds / 86400.0);
  double rest = seconds - days * 86400.0;
  CivilDateTime t;
  t.date = civil_from_days(static_cast<std::int64_t>(days));
  t.hour = static_cast<int>(rest / 3600.0);
  rest -= t.hour * 3600.0;
  t.minute = static_cast<int>(rest / 60.0);
  t.second = rest - t.minute * 60.0;
  return t;
}

double julian_day_from_day_of_year(int year, int day_of_year, double hours_utc) {
  const std::int64_t jan1 = days_from_civil({year, 1, 1});
  return julian_day_from_unix((static_cast<double>(jan1 + day_of_year - 1)) * 86400.0 + hours_utc * 3600.0);
}

double decimal_year_from_unix(double unix_time_utc) {
  const CivilDate d = civil_from_days(static_cast<std::int64_t>(std::floor(unix_time_utc / 86400.0)));
  const double start = static_cast<double>(days_from_civil({d.year, 1, 1})) * 86400.0;
  const double end = static_cast<double>(days_from_civil({d.year + 1, 1, 1})) * 86400.0;
  return d.year + (unix_time_utc - start) / (end - start);
}

namespace {

std::string format_wall(double wall_seconds, int decimals) {
  // Integer ticks so that 59.9996 s rounds into the next minute instead of printing "60".
  decimals = decimals < 0 ? 0 : (decimals > 9 ? 9 : decimals);
  std::int64_t ticks_per_second = 1;
  for (int i = 0; i < decimals; ++i) ticks_per_second *= 10;
  const std::int64_t ticks = std::llround(wall_seconds * static_cast<double>(ticks_per_second));
  const std::int64_t ticks_per_day = 86400 * ticks_per_second;
  const std::int64_t days = floor_div(ticks, ticks_per_day);
  const std::int64_t in_day = ticks - days * ticks_per_day;
  const std::int64_t whole_seconds = in_day / ticks_per_second;
  const std::int64_t fraction = in_day % ticks_per_second;
  const CivilDate d = civil_from_days(days);
  char year[16];
  if (d.year >= 0 && d.year <= 9999) {
    std::snprintf(year, sizeof year, "%04d", d.year);
  } else {
    std::snprintf(year, sizeof year, "%+05d", d.year);
  }
  char text[128];
  const int hour = static_cast<int>(whole_seconds / 3600), minute = static_cast<int>(whole_seconds / 60 % 60),
            second = static_cast<int>(whole_seconds % 60);
  if (decimals > 0) {
    std::snprintf(text, sizeof text, "%s-%02d-%02dT%02d:%02d:%02d.%0*d", year, d.month, d.day, hour, minute, second,
                  decimals, static_cast<int>(fraction));
  } else {
    std::snprintf(text, sizeof text, "%s-%02d-%02dT%02d:%02d:%02d", year, d.month, d.day, hour, minute, second);
  }
  return text;
}

}  // namespace

std::string format_iso_utc(double unix_time_utc, int decimals) { return format_wall(unix_time_utc, decimals) + "Z"; }

std::string format_iso_local(double unix_time_utc, double utc_offset_s, int decimals) {
  // Offsets are below a day; the modulo only keeps the compiler's length analysis bounded. Local
  // mean time (Amsterdam until 1937: +00:19:32) keeps its seconds, so that the wall time and the
  // offset still give the instant back; rounding them to minutes put the time 28 s off.
  const long offset_s = std::lround(utc_offset_s);
  const long magnitude = (offset_s < 0 ? -offset_s : offset_s) % 86400;
  char zone[16];
  if (magnitude % 60 == 0) {
    std::snprintf(zone, sizeof zone, "%c%02ld:%02ld", offset_s < 0 ? '-' : '+', magnitude / 3600, magnitude / 60 % 60);
  } else {
    std::snprintf(zone, sizeof zone, "%c%02ld:%02ld:%02ld", offset_s < 0 ? '-' : '+', magnitude / 3600,
                  magnitude / 60 % 60, magnitude % 60);
  }
  return format_wall(unix_time_utc + static_cast<double>(offset_s), decimals) + zone;
}

}  // namespace skyview
