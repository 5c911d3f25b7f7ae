// The NREL Solar Position Algorithm, written from the equations of I. Reda, A. Andreas,
// "Solar position algorithm for solar radiation applications", Solar Energy 76(5):577-589, 2004
// and NREL/TP-560-34302 (revised 2008). Equation numbers below are the report's.
#include <cmath>
#include <cstdio>
#include <string>

#include "skyview/solar/civil_time.h"
#include "skyview/solar/delta_t.h"
#include "skyview/core/error.h"
#include "skyview/solar/solar_position.h"
#include "skyview/solar/time_parse.h"
#include "spa_geocentric.h"
#include "spa_tables.h"

namespace skyview {

namespace spa {

double wrap_degrees(double d) {
  d = std::fmod(d, 360.0);
  return d < 0.0 ? d + 360.0 : d;
}

double wrap_signed_degrees(double d) {
  d = wrap_degrees(d + 180.0) - 180.0;
  return d;
}

namespace {

// Eqs. 9-12: a power series in JME whose coefficients are sums of periodic terms.
double earth_series(const TermSeries* series, int powers, double jme) {
  double total = 0.0, jme_power = 1.0;
  for (int p = 0; p < powers; ++p) {
    double sum = 0.0;
    for (int i = 0; i < series[p].count; ++i) {
      const PeriodicTerm& t = series[p].terms[i];
      sum += t.a * std::cos(t.b + t.c * jme);
    }
    total += sum * jme_power;
    jme_power *= jme;
  }
  return total / 1e8;
}

double polynomial(double x, double c0, double c1, double c2, double c3_divisor) {
  return c0 + x * (c1 + x * (c2 + x / c3_divisor));
}

}  // namespace

void compute_geocentric(double jd, double delta_t_s, SpaResult& r) {
  // 3.1 time scales (Eqs. 4-8).
  r.julian_day = jd;
  r.delta_t_s = delta_t_s;
  r.julian_ephemeris_day = jd + delta_t_s / 86400.0;
  r.julian_century = (jd - 2451545.0) / 36525.0;
  r.julian_ephemeris_century = (r.julian_ephemeris_day - 2451545.0) / 36525.0;
  r.julian_ephemeris_millennium = r.julian_ephemeris_century / 10.0;
  const double jc = r.julian_century, jce = r.julian_ephemeris_century, jme = r.julian_ephemeris_millennium;

  // 3.2 heliocentric position of the Earth (Eqs. 9-14), 3.3 geocentric sun (Eqs. 13-14).
  r.heliocentric_longitude = wrap_degrees(deg(earth_series(kLSeries, 6, jme)));
  r.heliocentric_latitude = deg(earth_series(kBSeries, 2, jme));
  r.earth_sun_distance_au = earth_series(kRSeries, 5, jme);
  r.geocentric_longitude = wrap_degrees(r.heliocentric_longitude + 180.0);
  r.geocentric_latitude = -r.heliocentric_latitude;

  // 3.4 nutation (Eqs. 15-23). The cubic terms are given as divisors in the report.
  double* x = r.nutation_arguments;
  x[0] = polynomial(jce, 297.85036, 445267.111480, -0.0019142, 189474.0);
  x[1] = polynomial(jce, 357.52772, 35999.050340, -0.0001603, -300000.0);
  x[2] = polynomial(jce, 134.96298, 477198.867398, 0.0086972, 56250.0);
  x[3] = polynomial(jce, 93.27191, 483202.017538, -0.0036825, 327270.0);
  x[4] = polynomial(jce, 125.04452, -1934.136261, 0.0020708, 450000.0);
  double dpsi = 0.0, deps = 0.0;
  for (const NutationTerm& t : kNutationTerms) {
    double argument = 0.0;
    for (int j = 0; j < 5; ++j) argument += x[j] * t.y[j];
    argument = rad(argument);
    dpsi += (t.a + t.b * jce) * std::sin(argument);
    deps += (t.c + t.d * jce) * std::cos(argument);
  }
  r.nutation_longitude = dpsi / 36000000.0;
  r.nutation_obliquity = deps / 36000000.0;

  // 3.5 obliquity (Eqs. 24-25).
  const double u = jme / 10.0;
  r.mean_obliquity_arcsec =
      84381.448 +
      u * (-4680.93 +
           u * (-1.55 +
                u * (1999.25 +
                     u * (-51.38 + u * (-249.67 + u * (-39.05 + u * (7.12 + u * (27.87 + u * (5.79 + u * 2.45)))))))));
  r.true_obliquity = r.mean_obliquity_arcsec / 3600.0 + r.nutation_obliquity;

  // 3.6-3.7 aberration and apparent longitude (Eqs. 26-27).
  r.aberration = -20.4898 / (3600.0 * r.earth_sun_distance_au);
  r.apparent_sun_longitude = r.geocentric_longitude + r.nutation_longitude + r.aberration;

  // 3.8 sidereal time at Greenwich (Eqs. 28-29); it uses UT, not ephemeris time.
  r.mean_sidereal_time =
      wrap_degrees(280.46061837 + 360.98564736629 * (jd - 2451545.0) + jc * jc * (0.000387933 - jc / 38710000.0));
  const double eps = rad(r.true_obliquity);
  r.apparent_sidereal_time = r.mean_sidereal_time + r.nutation_longitude * std::cos(eps);

  // 3.9-3.10 geocentric right ascension and declination (Eqs. 30-31).
  const double lambda = rad(r.apparent_sun_longitude), beta = rad(r.geocentric_latitude);
  r.geocentric_right_ascension = wrap_degrees(
      deg(std::atan2(std::sin(lambda) * std::cos(eps) - std::tan(beta) * std::sin(eps), std::cos(lambda))));
  r.geocentric_declination =
      deg(std::asin(std::sin(beta) * std::cos(eps) + std::cos(beta) * std::sin(eps) * std::sin(lambda)));
}

}  // namespace spa

using spa::deg;
using spa::rad;
using spa::wrap_degrees;

namespace {

std::string number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}

}  // namespace

void validate_site(const Site& s) {
  auto require = [](bool ok, const std::string& what) {
    if (!ok) throw Error(what);
  };
  require(std::isfinite(s.latitude_deg) && std::abs(s.latitude_deg) <= 90.0,
          "latitude " + number_text(s.latitude_deg) + " is outside -90..90 degrees");
  require(std::isfinite(s.longitude_deg) && std::abs(s.longitude_deg) <= 180.0,
          "longitude " + number_text(s.longitude_deg) + " is outside -180..180 degrees");
  require(std::isfinite(s.elevation_m) && s.elevation_m >= -6500000.0 && s.elevation_m <= 100000.0,
          "elevation " + number_text(s.elevation_m) + " m is outside -6500000..100000 m");
  require(std::isfinite(s.pressure_mbar) && s.pressure_mbar >= 0.0 && s.pressure_mbar <= 5000.0,
          "pressure " + number_text(s.pressure_mbar) + " mbar is outside 0..5000 mbar");
  require(std::isfinite(s.temperature_c) && s.temperature_c > -273.15 && s.temperature_c <= 6000.0,
          "temperature " + number_text(s.temperature_c) + " C is outside -273.15..6000 C");
  require(std::isfinite(s.delta_ut1_s) && std::abs(s.delta_ut1_s) < 1.0,
          "UT1-UTC " + number_text(s.delta_ut1_s) + " s is outside -1..1 s");
  require(std::isfinite(s.delta_t_s) && (s.delta_t_s <= -1e8 || std::abs(s.delta_t_s) <= 1e6),
          "Delta T " + number_text(s.delta_t_s) + " s is outside -1e6..1e6 s");
}

namespace {

void check_year(double julian_day_ut) {
  const double days = std::floor(julian_day_ut - kUnixEpochJulianDay);
  const bool finite = std::isfinite(julian_day_ut) && std::abs(days) < 1e9;
  const int year = finite ? civil_from_days(static_cast<std::int64_t>(days)).year : 0;
  if (!finite || year < kMinSolarYear || year > kMaxSolarYear) {
    throw Error("date outside the solar position range (years " + std::to_string(kMinSolarYear) + ".." +
                std::to_string(kMaxSolarYear) + ")");
  }
}

// Eq. 42: Bennett-type refraction scaled by pressure and temperature, only when the sun is
// above the apparent horizon (sun radius 0.26667 deg plus refraction 0.5667 deg at the horizon).
double refraction_deg(double e0, const Site& s) {
  if (e0 < -(0.26667 + 0.5667)) return 0.0;
  return (s.pressure_mbar / 1010.0) * (283.0 / (273.0 + s.temperature_c)) * 1.02 /
         (60.0 * std::tan(rad(e0 + 10.3 / (e0 + 5.11))));
}

// Appendix A.1: equation of time from the sun's mean longitude, in minutes within +-20.
double equation_of_time_min(const SpaResult& r) {
  const double jme = r.julian_ephemeris_millennium;
  const double mean_longitude = wrap_degrees(
      280.4664567 +
      jme * (360007.6982779 + jme * (0.03032028 + jme * (1.0 / 49931.0 + jme * (-1.0 / 15300.0 - jme / 2000000.0)))));
  double minutes = 4.0 * (mean_longitude - 0.0057183 - r.geocentric_right_ascension +
                          r.nutation_longitude * std::cos(rad(r.true_obliquity)));
  if (minutes > 20.0) minutes -= 1440.0;
  if (minutes < -20.0) minutes += 1440.0;
  return minutes;
}

}  // namespace

double resolved_delta_t_s(double julian_day_ut, const Site& site) {
  if (site.delta_t_s > -1e8) return site.delta_t_s;
  return automatic_delta_t_s(decimal_year_from_unix(unix_from_julian_day(julian_day_ut)));
}

SpaResult spa_compute(double julian_day_ut, const Site& site) {
  validate_site(site);
  check_year(julian_day_ut);
  const double jd = julian_day_ut + site.delta_ut1_s / 86400.0;
  SpaResult r;
  spa::compute_geocentric(jd, resolved_delta_t_s(julian_day_ut, site), r);

  // 3.9 observer local hour angle (Eq. 32).
  r.local_hour_angle = wrap_degrees(r.apparent_sidereal_time + site.longitude_deg - r.geocentric_right_ascension);

  // 3.10-3.11 parallax: topocentric right ascension, declination, hour angle (Eqs. 33-40).
  const double phi = rad(site.latitude_deg);
  r.equatorial_parallax = 8.794 / (3600.0 * r.earth_sun_distance_au);
  const double xi = rad(r.equatorial_parallax);
  const double u = std::atan(0.99664719 * std::tan(phi));
  const double height = site.elevation_m / 6378140.0;
  const double x = std::cos(u) + height * std::cos(phi);
  const double y = 0.99664719 * std::sin(u) + height * std::sin(phi);
  const double h = rad(r.local_hour_angle), delta = rad(r.geocentric_declination);
  const double denominator = std::cos(delta) - x * std::sin(xi) * std::cos(h);
  const double d_alpha = std::atan2(-x * std::sin(xi) * std::sin(h), denominator);
  r.parallax_right_ascension = deg(d_alpha);
  r.topocentric_right_ascension = r.geocentric_right_ascension + r.parallax_right_ascension;
  r.topocentric_declination = deg(std::atan2((std::sin(delta) - y * std::sin(xi)) * std::cos(d_alpha), denominator));
  r.topocentric_hour_angle = r.local_hour_angle - r.parallax_right_ascension;

  // 3.12-3.14 elevation, refraction, zenith (Eqs. 41-44).
  const double delta_p = rad(r.topocentric_declination), h_p = rad(r.topocentric_hour_angle);
  r.elevation_unrefracted =
      deg(std::asin(std::sin(phi) * std::sin(delta_p) + std::cos(phi) * std::cos(delta_p) * std::cos(h_p)));
  r.refraction = refraction_deg(r.elevation_unrefracted, site);
  r.elevation = r.elevation_unrefracted + r.refraction;
  r.zenith = 90.0 - r.elevation;

  // 3.15 azimuth (Eqs. 45-46): astronomers' from south, then navigators' from north.
  r.azimuth_from_south =
      wrap_degrees(deg(std::atan2(std::sin(h_p), std::cos(h_p) * std::sin(phi) - std::tan(delta_p) * std::cos(phi))));
  r.azimuth = wrap_degrees(r.azimuth_from_south + 180.0);

  r.equation_of_time_min = equation_of_time_min(r);
  return r;
}

SunPosition solar_position_at_julian_day(double julian_day_ut, const Site& site) {
  const SpaResult r = spa_compute(julian_day_ut, site);
  SunPosition p;
  p.zenith_deg = r.zenith;
  p.azimuth_deg = r.azimuth;
  p.elevation_deg = r.elevation;
  p.declination_deg = r.topocentric_declination;
  p.right_ascension_deg = wrap_degrees(r.topocentric_right_ascension);
  p.earth_sun_distance_au = r.earth_sun_distance_au;
  p.equation_of_time_min = r.equation_of_time_min;
  p.delta_t_s = r.delta_t_s;
  return p;
}

SunPosition solar_position(double unix_time_utc, const Site& site) {
  return solar_position_at_julian_day(julian_day_from_unix(unix_time_utc), site);
}

double incidence_angle_deg(double zenith_deg, double azimuth_deg, double slope_deg, double surface_azimuth_deg) {
  // Eq. 47 with the surface azimuth rotation taken from north; the cosine of the difference
  // is the same whichever reference both azimuths share.
  const double z = rad(zenith_deg), w = rad(slope_deg);
  const double c =
      std::cos(z) * std::cos(w) + std::sin(w) * std::sin(z) * std::cos(rad(azimuth_deg - surface_azimuth_deg));
  return deg(std::acos(std::fmax(-1.0, std::fmin(1.0, c))));
}

}  // namespace skyview
