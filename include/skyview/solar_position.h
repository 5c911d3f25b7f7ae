#pragma once
// Where the sun is: the NREL Solar Position Algorithm (Reda & Andreas 2004/2008), topocentric,
// with refraction. Times are UTC seconds since 1970-01-01T00:00:00Z (negative before), valid for
// years -2000 .. 6000 as SPA allows.
#include <optional>

namespace skyview {

struct Site {
  double latitude_deg = 0.0;     // north positive
  double longitude_deg = 0.0;    // east positive
  double elevation_m = 0.0;
  double pressure_mbar = 1013.25;
  double temperature_c = 15.0;
  double delta_t_s = -1e9;       // TT - UT1 in seconds; <= -1e8 means "choose automatically"
  double delta_ut1_s = 0.0;
};

struct SunPosition {
  double zenith_deg = 0;     // topocentric, refracted
  double azimuth_deg = 0;    // clockwise from north, [0, 360)
  double elevation_deg = 0;  // 90 - zenith
  double declination_deg = 0;        // topocentric
  double right_ascension_deg = 0;    // topocentric
  double earth_sun_distance_au = 1;  // R
  double equation_of_time_min = 0;
  double delta_t_s = 0;              // the value used
};

// Throws skyview::Error for out-of-range inputs (latitude, dates outside -2000..6000 ...).
SunPosition solar_position(double unix_time_utc, const Site& site);

}  // namespace skyview
