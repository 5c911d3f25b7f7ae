#pragma once
// Where the sun is: the NREL Solar Position Algorithm (Reda & Andreas 2004/2008), topocentric,
// with refraction. Times are UTC seconds since 1970-01-01T00:00:00Z (negative before), valid for
// years -2000 .. 6000 as SPA allows.
#include <optional>

namespace skyview {

struct Site {
  double latitude_deg = 0.0;   // north positive
  double longitude_deg = 0.0;  // east positive
  double elevation_m = 0.0;
  double pressure_mbar = 1013.25;
  double temperature_c = 15.0;
  double delta_t_s = -1e9;  // TT - UT1 in seconds; <= -1e8 means "choose automatically"
  double delta_ut1_s = 0.0;
};

struct SunPosition {
  double zenith_deg = 0;             // topocentric, refracted
  double azimuth_deg = 0;            // clockwise from north, [0, 360)
  double elevation_deg = 0;          // 90 - zenith
  double declination_deg = 0;        // topocentric
  double right_ascension_deg = 0;    // topocentric
  double earth_sun_distance_au = 1;  // R
  double equation_of_time_min = 0;
  double delta_t_s = 0;  // the value used
};

// Throws skyview::Error for out-of-range inputs (latitude, dates outside -2000..6000 ...).
SunPosition solar_position(double unix_time_utc, const Site& site);

// ---- Lower level: the SPA with every intermediate, and the Julian-date entry point. ----

// The SPA's quantities for one instant, named as in Reda & Andreas (2008); angles in degrees.
struct SpaResult {
  double julian_day = 0;            // JD (UT)
  double julian_ephemeris_day = 0;  // JDE = JD + delta_t / 86400
  double julian_century = 0, julian_ephemeris_century = 0, julian_ephemeris_millennium = 0;
  double delta_t_s = 0;
  double heliocentric_longitude = 0;       // L, [0, 360)
  double heliocentric_latitude = 0;        // B
  double earth_sun_distance_au = 0;        // R
  double geocentric_longitude = 0;         // Theta
  double geocentric_latitude = 0;          // beta
  double nutation_arguments[5] = {};       // X0..X4
  double nutation_longitude = 0;           // delta psi
  double nutation_obliquity = 0;           // delta epsilon
  double mean_obliquity_arcsec = 0;        // epsilon0
  double true_obliquity = 0;               // epsilon
  double aberration = 0;                   // delta tau
  double apparent_sun_longitude = 0;       // lambda
  double mean_sidereal_time = 0;           // nu0, Greenwich
  double apparent_sidereal_time = 0;       // nu, Greenwich
  double geocentric_right_ascension = 0;   // alpha
  double geocentric_declination = 0;       // delta
  double local_hour_angle = 0;             // H
  double equatorial_parallax = 0;          // xi
  double parallax_right_ascension = 0;     // delta alpha
  double topocentric_right_ascension = 0;  // alpha'
  double topocentric_declination = 0;      // delta'
  double topocentric_hour_angle = 0;       // H'
  double elevation_unrefracted = 0;        // e0
  double refraction = 0;                   // delta e
  double elevation = 0;                    // e = e0 + delta e
  double zenith = 0;                       // theta = 90 - e
  double azimuth_from_south = 0;           // Gamma, astronomers' (westward from south)
  double azimuth = 0;                      // Phi, clockwise from north, [0, 360)
  double equation_of_time_min = 0;         // EOT, minutes in [-20, 20]
};

// The whole SPA at Julian day `julian_day_ut` (UT; site.delta_ut1_s is added). The Unix-time
// entry point solar_position() and day-of-year inputs (civil_time.h) both arrive here.
SpaResult spa_compute(double julian_day_ut, const Site& site);

// solar_position() for a Julian day (UT) instead of a Unix time: the same computation.
SunPosition solar_position_at_julian_day(double julian_day_ut, const Site& site);

// The Delta T the SPA uses at that Julian day: site.delta_t_s, or automatic_delta_t_s().
double resolved_delta_t_s(double julian_day_ut, const Site& site);

// Throws skyview::Error unless the site's values are physically meaningful (SPA's input limits).
void validate_site(const Site& site);

// Incidence angle (degrees) of the sun on a plane tilted `slope_deg` from horizontal whose
// downslope direction faces `surface_azimuth_deg` (clockwise from north); SPA Eq. 47.
double incidence_angle_deg(double zenith_deg, double azimuth_deg, double slope_deg, double surface_azimuth_deg);

}  // namespace skyview
