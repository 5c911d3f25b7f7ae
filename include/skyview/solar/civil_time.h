#pragma once
// Calendar arithmetic for the proleptic Gregorian calendar (astronomical year numbering: year 0
// is 1 BC), written out by hand so that it covers the SPA range -2000..6000 without relying on
// the C library's time_t or tm conversions.
#include <cstdint>
#include <string>

namespace skyview {

struct CivilDate {
  int year = 1970, month = 1, day = 1;
};

struct CivilDateTime {
  CivilDate date;
  int hour = 0, minute = 0;
  double second = 0.0;
};

// Days since 1970-01-01 of a proleptic Gregorian date, and back.
std::int64_t days_from_civil(const CivilDate& d);
CivilDate civil_from_days(std::int64_t days);

// Seconds since 1970-01-01T00:00:00 of a wall-clock time read as if it were UTC, and back.
double seconds_from_civil(const CivilDateTime& t);
CivilDateTime civil_from_seconds(double seconds);

// Julian day (UT) of a Unix time, and back: JD 2440587.5 is 1970-01-01T00:00Z.
constexpr double kUnixEpochJulianDay = 2440587.5;
inline double julian_day_from_unix(double unix_time_utc) { return unix_time_utc / 86400.0 + kUnixEpochJulianDay; }
inline double unix_from_julian_day(double julian_day) { return (julian_day - kUnixEpochJulianDay) * 86400.0; }

// Julian day at `hours_utc` on day-of-year `day_of_year` (1 = January 1) of `year`.
double julian_day_from_day_of_year(int year, int day_of_year, double hours_utc);

// Year with fraction, e.g. 2003.79 for mid-October 2003 (for Delta T).
double decimal_year_from_unix(double unix_time_utc);

// "2003-10-17T19:30:30Z" (seconds rounded to `decimals`); with an offset in seconds,
// the local wall time followed by "+hh:mm" / "-hh:mm". Years outside 0..9999 get a sign.
std::string format_iso_utc(double unix_time_utc, int decimals = 0);
std::string format_iso_local(double unix_time_utc, double utc_offset_s, int decimals = 0);

}  // namespace skyview
