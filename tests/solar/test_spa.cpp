// The SPA report's worked example (Reda & Andreas 2008, Table A5.1/A5.2, NREL spa_tester.c)
// to its printed digits, with the intermediate values from the report and pvlib's tests.
#include <gtest/gtest.h>

#include <cmath>

#include "golden_site.h"
#include "skyview/solar/civil_time.h"
#include "skyview/core/error.h"
#include "skyview/solar/solar_position.h"
#include "skyview/solar/time_parse.h"

using namespace skyview;

namespace {

using skyview::test::golden_site;

double golden_time() { return parse_time("2003-10-17T12:30:30-07:00").unix_utc; }

}  // namespace

TEST(SpaTestCase, TimeScalesAndEarthPosition) {
  const SpaResult r = spa_compute(julian_day_from_unix(golden_time()), golden_site());
  EXPECT_NEAR(r.julian_day, 2452930.312847, 5e-7);
  EXPECT_NEAR(r.julian_ephemeris_day, 2452930.313623, 5e-7);
  // pvlib's test starts from JD rounded to 1e-6 day, i.e. JC within 1.4e-11.
  EXPECT_NEAR(r.julian_century, 0.0379277986858, 2e-11);
  EXPECT_NEAR(r.julian_ephemeris_millennium, 0.003792781991685, 2e-12);
  EXPECT_NEAR(r.heliocentric_longitude, 24.0182616917, 5e-11);
  EXPECT_NEAR(r.heliocentric_latitude, -0.0001011219, 5e-11);
  EXPECT_NEAR(r.earth_sun_distance_au, 0.9965422974, 5e-11);
  EXPECT_NEAR(r.geocentric_longitude, 204.0182616917, 5e-11);
}

TEST(SpaTestCase, NutationObliquityAndSiderealTime) {
  const SpaResult r = spa_compute(julian_day_from_unix(golden_time()), golden_site());
  EXPECT_NEAR(r.nutation_arguments[0], 17185.861179, 5e-7);
  EXPECT_NEAR(r.nutation_arguments[4], 51.686951, 5e-7);
  EXPECT_NEAR(r.nutation_longitude, -0.003998404, 5e-10);
  EXPECT_NEAR(r.nutation_obliquity, 0.001666568, 5e-10);
  EXPECT_NEAR(r.mean_obliquity_arcsec, 84379.672625, 5e-7);
  EXPECT_NEAR(r.true_obliquity, 23.440465, 5e-7);
  EXPECT_NEAR(r.aberration, -0.005711, 5e-7);
  EXPECT_NEAR(r.apparent_sun_longitude, 204.0085519281, 5e-10);
  EXPECT_NEAR(r.mean_sidereal_time, 318.515579, 1e-6);  // pvlib test value, last digit differs
  EXPECT_NEAR(r.apparent_sidereal_time, 318.511910, 5e-7);
  EXPECT_NEAR(r.geocentric_right_ascension, 202.227408, 5e-7);
  EXPECT_NEAR(r.geocentric_declination, -9.31434, 5e-6);
}

TEST(SpaTestCase, TopocentricZenithAzimuthIncidence) {
  const SpaResult r = spa_compute(julian_day_from_unix(golden_time()), golden_site());
  EXPECT_NEAR(r.local_hour_angle, 11.105902, 5e-7);
  EXPECT_NEAR(r.equatorial_parallax, 0.002451, 5e-7);
  EXPECT_NEAR(r.parallax_right_ascension, -0.000369, 5e-7);
  EXPECT_NEAR(r.topocentric_right_ascension, 202.22704, 5e-6);
  EXPECT_NEAR(r.topocentric_declination, -9.316179, 5e-7);
  EXPECT_NEAR(r.topocentric_hour_angle, 11.10627, 5e-6);
  EXPECT_NEAR(r.elevation_unrefracted, 39.872046, 5e-7);
  EXPECT_NEAR(r.refraction, 0.016332, 5e-7);
  EXPECT_NEAR(r.zenith, 50.111622, 5e-7);
  EXPECT_NEAR(r.azimuth_from_south, 14.340241, 5e-7);
  EXPECT_NEAR(r.azimuth, 194.340241, 5e-7);
  EXPECT_NEAR(r.equation_of_time_min, 14.6415107708, 5e-7);
  // Surface slope 30 deg, azimuth rotation -10 deg from south = 170 deg from north.
  EXPECT_NEAR(incidence_angle_deg(r.zenith, r.azimuth, 30.0, 170.0), 25.187000, 5e-7);
}

TEST(SpaTestCase, PublicApiMatchesLowLevel) {
  const SunPosition p = solar_position(golden_time(), golden_site());
  EXPECT_NEAR(p.zenith_deg, 50.11162, 5e-6);
  EXPECT_NEAR(p.azimuth_deg, 194.34024, 5e-6);
  EXPECT_NEAR(p.elevation_deg, 90.0 - 50.111622, 5e-7);
  EXPECT_NEAR(p.declination_deg, -9.316179, 5e-7);
  EXPECT_NEAR(p.earth_sun_distance_au, 0.9965422974, 5e-11);
  EXPECT_DOUBLE_EQ(p.delta_t_s, 67.0);
}

// The hybrid-shadow-maps paper drives the sun by Julian date (day of year and time): that
// path enters the same spa_compute, so the results are identical, not merely close.
TEST(SpaJulianDatePath, DayOfYearIsTheSameComputation) {
  Site utm;
  utm.latitude_deg = 1.28;
  utm.longitude_deg = 103.45;
  const double jd = julian_day_from_day_of_year(2011, 134, 4.0);  // 14 May 2011, 12:00 at UTC+8
  const double unix_time = parse_time("2011-05-14T12:00:00+08:00").unix_utc;
  EXPECT_DOUBLE_EQ(jd, julian_day_from_unix(unix_time));
  const SunPosition a = solar_position_at_julian_day(jd, utm);
  const SunPosition b = solar_position(unix_time, utm);
  EXPECT_EQ(a.zenith_deg, b.zenith_deg);
  EXPECT_EQ(a.azimuth_deg, b.azimuth_deg);
  EXPECT_GT(a.elevation_deg, 60.0);  // near noon, 1.3 deg from the equator in May
}

TEST(SpaRange, RejectsDatesOutsideMinus2000To6000) {
  const Site s = golden_site();
  EXPECT_THROW(solar_position(seconds_from_civil({{6001, 1, 1}}), s), Error);
  EXPECT_THROW(solar_position(seconds_from_civil({{-2001, 12, 31}}), s), Error);
  EXPECT_NO_THROW(solar_position(seconds_from_civil({{6000, 12, 31}}), s));
  EXPECT_NO_THROW(solar_position(seconds_from_civil({{-2000, 1, 1}}), s));
  EXPECT_THROW(solar_position(std::nan(""), s), Error);
}

TEST(SpaRange, RejectsBadSites) {
  Site s = golden_site();
  s.latitude_deg = 91.0;
  EXPECT_THROW(solar_position(golden_time(), s), Error);
  s = golden_site();
  s.longitude_deg = -181.0;
  EXPECT_THROW(solar_position(golden_time(), s), Error);
  s = golden_site();
  s.pressure_mbar = -1.0;
  EXPECT_THROW(solar_position(golden_time(), s), Error);
  s = golden_site();
  s.temperature_c = -300.0;
  EXPECT_THROW(solar_position(golden_time(), s), Error);
}

// Refraction only lifts the sun; without air (pressure 0) the zenith is geometric.
TEST(SpaRefraction, ZeroPressureGivesUnrefractedZenith) {
  Site s = golden_site();
  s.pressure_mbar = 0.0;
  const SpaResult r = spa_compute(julian_day_from_unix(golden_time()), s);
  EXPECT_NEAR(r.zenith, 50.1279540962, 5e-7);
  EXPECT_EQ(r.refraction, 0.0);
}
