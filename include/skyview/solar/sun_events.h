#pragma once
// Sunrise, sun transit and sunset for one day by the SPA's method (Reda & Andreas 2008,
// Appendix A.2): geocentric positions at 0 TT of three days, interpolated, then corrected.
#include <optional>

#include "skyview/solar/civil_time.h"
#include "skyview/solar/solar_position.h"

namespace skyview {

// Altitude of the sun's centre at rise and set: its radius 0.26667 deg plus a standard
// horizon refraction of 0.5667 deg, below the geometric horizon (SPA's h0').
constexpr double kSunriseAltitudeDeg = -(0.26667 + 0.5667);

enum class SunEventDay {
  // The events of the local calendar day: the transit nearest local noon and the sunrise and
  // sunset around it (for the SPA test case: sunset 17:18:51 on 2003-10-17).
  local_day,
  // SPA's own convention: the events are fractions of the UT day with the same calendar date,
  // each wrapped into that UT day (for the test case: sunset 17:20:19 local, which is in fact
  // the sunset of the evening before, 00:20:19 UT on 2003-10-17).
  spa_utc_day,
};

// normal: a sunrise and a sunset. The days that begin and end polar day and night have one of
// them only: the sun rises and stays up past the next lower culmination (no_sunset), or has been
// up since the last one and sets (no_sunrise).
enum class DayKind { normal, polar_day, polar_night, no_sunset, no_sunrise };

struct SunEvents {
  DayKind kind = DayKind::normal;
  double transit_utc = 0.0;            // Unix time of the sun's meridian transit
  std::optional<double> sunrise_utc;   // absent in polar day and night, and on a no_sunrise day
  std::optional<double> sunset_utc;    // absent in polar day and night, and on a no_sunset day
  double transit_elevation_deg = 0.0;  // topocentric, refracted, at transit
  // Half a day either side of the transit: the lower culminations, to within seconds.
  double lower_before_utc = 0.0, lower_after_utc = 0.0;
  // Hours the sun spends above the rise-and-set altitude between the lower culminations around the
  // transit: sunset minus sunrise on a normal day, 24 in polar day and 0 in polar night.
  double day_length_h() const;
};

// Events for calendar day `date` in a place whose clocks are `utc_offset_s` ahead of UTC that
// day (only local_day uses the offset). Polar day and night are answers (`kind`), not errors.
// local_day judges the day by the sun's geometric altitude at its transit and lower culminations
// and takes each event from SPA's estimate by Newton steps on that altitude (bisection where they
// fail: on the days around polar day and night the estimate from one declination can be hours
// off); spa_utc_day is the report's algorithm as published, those days included.
SunEvents sun_events(const CivilDate& date, double utc_offset_s, const Site& site,
                     SunEventDay convention = SunEventDay::local_day,
                     double sunrise_altitude_deg = kSunriseAltitudeDeg);

}  // namespace skyview
