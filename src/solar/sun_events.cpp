// Sunrise, transit and sunset following Reda & Andreas (2008), Appendix A.2, with two
// deliberate differences: the right-ascension differences are unwrapped across 0/360 deg
// (the report's "limit to 0..1" misreads them near the March equinox), and by default the
// transit is the one nearest local noon instead of the first in the UT day.
#include "skyview/solar/sun_events.h"

#include <cmath>

#include "spa_geocentric.h"

namespace skyview {

using spa::deg;
using spa::rad;

namespace {

double wrap_unit(double x) { return x - std::floor(x); }

// Daily change of a right ascension, taking the short way round the circle.
double unwrapped_difference(double later, double earlier) {
  double d = later - earlier;
  if (d > 180.0) d -= 360.0;
  if (d < -180.0) d += 360.0;
  return d;
}

struct ThreeDays {
  double alpha[3], delta[3];  // day before, day, day after, at 0 TT
};

// Eq. A.6-A.8: quadratic interpolation at `n` days after 0 TT of the middle day.
double interpolate(double value, double a, double b, double n) { return value + n * (a + b + (b - a) * n) / 2.0; }

// SPA's rise and set come from one hour angle H0 at the day's declination, then one correction
// that divides by sin H: near polar day and night, where H0 is close to 0 or 180 deg, the day's
// kind can come out wrong and the times hours off (Tromso, 27 November 2024: sunrise 11:48, transit
// 11:32, sunset 11:13, called normal, with the sun 0.9 deg under its rise altitude at transit).
// So the day is judged by the sun's geometric altitude (no refraction: h0 already holds the
// standard one) at its transit and half a day either side (the lower culminations), and each
// event is the crossing of h0 between two of them, found from SPA's estimate where that is good.
double geometric_altitude(double t, const Site& site) {
  Site bare = site;
  bare.pressure_mbar = 0.0;
  return solar_position(t, bare).elevation_deg;
}

// The time in [lo, hi] where the altitude crosses h0, rising (altitude below h0 at lo) or setting.
double bisect_crossing(double lo, double hi, const Site& site, double h0, bool rising) {
  for (int i = 0; i < 40 && hi - lo > 0.01; ++i) {
    const double mid = 0.5 * (lo + hi);
    const bool above = geometric_altitude(mid, site) >= h0;
    (above == rising ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

// The crossing of h0 in (lo, hi), from SPA's estimate where there is one: Newton steps on the
// altitude (its rate from a 10 s difference). SPA's time stands where the first step is under a
// second (at mid-latitudes; the topocentric altitude holds the parallax that the report's
// geocentric A.2 leaves out, 2 s at 60 N); the steps go on to 0.01 s where it is off (near
// polar day and night the altitude changes slowly, and an estimate 0.014 deg off was 6.5 minutes
// off at 66 N); bisection where they leave the bracket or the estimate is missing.
double crossing(const std::optional<double>& estimate, double lo, double hi, const Site& site, double h0, bool rising) {
  if (estimate && *estimate > lo && *estimate < hi) {
    double t = *estimate;
    for (int i = 0; i < 12; ++i) {
      const double a = geometric_altitude(t, site) - h0;
      const double rate = (geometric_altitude(t + 10.0, site) - h0 - a) / 10.0;
      if (!(rising ? rate > 0.0 : rate < 0.0)) break;
      const double step = -a / rate;
      if (i == 0 && std::abs(step) < 1.0) return t;
      t += step;
      if (!(t > lo && t < hi)) break;
      if (std::abs(step) < 0.01) return t;
    }
  }
  return bisect_crossing(lo, hi, site, h0, rising);
}

void check_against_altitudes(SunEvents& e, const Site& site, double h0) {
  const double before = e.lower_before_utc, transit = e.transit_utc, after = e.lower_after_utc;
  const bool up_before = geometric_altitude(before, site) >= h0;
  const bool up_at_transit = geometric_altitude(transit, site) >= h0;
  const bool up_after = geometric_altitude(after, site) >= h0;
  // The sun rises between a lower culmination and the transit, and sets after; within a tenth of a
  // degree of a pole, where the daily swing is smaller than the declination's change, it can also
  // rise after the transit (or set before it).
  std::optional<double> sunrise, sunset;
  if (!up_before && up_at_transit)
    sunrise = crossing(e.sunrise_utc, before, transit, site, h0, true);
  else if (!up_at_transit && up_after)
    sunrise = crossing(e.sunrise_utc, transit, after, site, h0, true);
  if (up_at_transit && !up_after)
    sunset = crossing(e.sunset_utc, transit, after, site, h0, false);
  else if (up_before && !up_at_transit)
    sunset = crossing(e.sunset_utc, before, transit, site, h0, false);
  e.sunrise_utc = sunrise;
  e.sunset_utc = sunset;
  if (sunrise && sunset)
    e.kind = DayKind::normal;
  else if (sunrise)
    e.kind = DayKind::no_sunset;
  else if (sunset)
    e.kind = DayKind::no_sunrise;
  else
    e.kind = up_at_transit ? DayKind::polar_day : DayKind::polar_night;
}

}  // namespace

double SunEvents::day_length_h() const {
  if (kind == DayKind::polar_day) return 24.0;
  if (kind == DayKind::polar_night) return 0.0;
  if (kind == DayKind::no_sunset) return (lower_after_utc - *sunrise_utc) / 3600.0;
  if (kind == DayKind::no_sunrise) return (*sunset_utc - lower_before_utc) / 3600.0;
  // In the SPA convention the sunset can precede the sunrise within the UT day.
  const double hours = (*sunset_utc - *sunrise_utc) / 3600.0;
  return hours < 0.0 ? hours + 24.0 : hours;
}

SunEvents sun_events(const CivilDate& date, double utc_offset_s, const Site& site, SunEventDay convention,
                     double sunrise_altitude_deg) {
  validate_site(site);
  // The UT day whose 0h anchors the computation, and where in it the local noon falls.
  double ut_day = static_cast<double>(days_from_civil(date));
  double local_noon_fraction = 0.5;
  if (convention == SunEventDay::local_day) {
    const double noon = (ut_day + 0.5) * 86400.0 - utc_offset_s;
    ut_day = std::floor(noon / 86400.0);
    local_noon_fraction = noon / 86400.0 - ut_day;
  }
  const double jd0 = julian_day_from_unix(ut_day * 86400.0);
  const double delta_t = resolved_delta_t_s(jd0, site);

  // A.2.1-A.2.2: apparent sidereal time at 0 UT, and alpha/delta at 0 TT (Delta T = 0).
  SpaResult at_0ut;
  spa::compute_geocentric(jd0, delta_t, at_0ut);
  const double nu = at_0ut.apparent_sidereal_time;
  ThreeDays days{};
  for (int i = 0; i < 3; ++i) {
    SpaResult r;
    spa::compute_geocentric(jd0 + i - 1, 0.0, r);
    days.alpha[i] = r.geocentric_right_ascension;
    days.delta[i] = r.geocentric_declination;
  }

  // A.2.3-A.2.5: approximate transit, then sunrise and sunset one local hour angle H0 away.
  const double phi = rad(site.latitude_deg), sigma = site.longitude_deg;
  double m[3];
  m[0] = (days.alpha[1] - sigma - nu) / 360.0;
  m[0] = convention == SunEventDay::local_day ? m[0] + std::round(local_noon_fraction - m[0]) : wrap_unit(m[0]);
  const double cos_h0 = (std::sin(rad(sunrise_altitude_deg)) - std::sin(phi) * std::sin(rad(days.delta[1]))) /
                        (std::cos(phi) * std::cos(rad(days.delta[1])));
  SunEvents events;
  const bool has_rise_set = std::abs(cos_h0) <= 1.0;
  if (!has_rise_set) events.kind = cos_h0 < -1.0 ? DayKind::polar_day : DayKind::polar_night;
  const double h0 = has_rise_set ? deg(std::acos(cos_h0)) : 0.0;
  m[1] = m[0] - h0 / 360.0;
  m[2] = m[0] + h0 / 360.0;
  if (convention == SunEventDay::spa_utc_day) {
    for (double& mi : m) mi = wrap_unit(mi);
  }

  // A.2.6-A.2.11: sidereal time, interpolated position, hour angle and altitude at each event.
  const double a_alpha = unwrapped_difference(days.alpha[1], days.alpha[0]);
  const double b_alpha = unwrapped_difference(days.alpha[2], days.alpha[1]);
  const double a_delta = days.delta[1] - days.delta[0], b_delta = days.delta[2] - days.delta[1];
  double hour_angle[3], altitude[3], declination[3];
  for (int i = 0; i < 3; ++i) {
    const double sidereal = nu + 360.985647 * m[i];
    const double n = m[i] + delta_t / 86400.0;
    const double alpha = interpolate(days.alpha[1], a_alpha, b_alpha, n);
    declination[i] = rad(interpolate(days.delta[1], a_delta, b_delta, n));
    hour_angle[i] = spa::wrap_signed_degrees(sidereal + sigma - alpha);
    altitude[i] = deg(std::asin(std::sin(phi) * std::sin(declination[i]) +
                                std::cos(phi) * std::cos(declination[i]) * std::cos(rad(hour_angle[i]))));
  }

  // A.2.12-A.2.14: corrected fractions of the day, turned into Unix times.
  auto at = [&](double fraction) { return (ut_day + fraction) * 86400.0; };
  events.transit_utc = at(m[0] - hour_angle[0] / 360.0);
  if (has_rise_set) {
    for (int i = 1; i <= 2; ++i) {
      const double correction = (altitude[i] - sunrise_altitude_deg) /
                                (360.0 * std::cos(declination[i]) * std::cos(phi) * std::sin(rad(hour_angle[i])));
      (i == 1 ? events.sunrise_utc : events.sunset_utc) = at(m[i] + correction);
    }
  }
  events.transit_elevation_deg = solar_position(events.transit_utc, site).elevation_deg;
  // Half a day either side of the transit is within seconds of the lower culminations (and, at the
  // poles, where the sun's altitude barely changes in a day, as good a bound as any).
  events.lower_before_utc = events.transit_utc - 43200.0;
  events.lower_after_utc = events.transit_utc + 43200.0;
  if (convention == SunEventDay::local_day) check_against_altitudes(events, site, sunrise_altitude_deg);
  return events;
}

}  // namespace skyview
