#pragma once
// The site-independent half of the SPA (report steps 3.1-3.8), shared by the position and the
// sunrise/transit/sunset computations.
#include "skyview/solar/solar_position.h"

namespace skyview::spa {

// Fills the time scales, L B R, nutation, obliquity, aberration, sidereal time and the
// geocentric right ascension/declination of `r` for Julian day `julian_day_ut` and `delta_t_s`.
void compute_geocentric(double julian_day_ut, double delta_t_s, SpaResult& r);

// Angle helpers shared by the solar files.
constexpr double kPi = 3.14159265358979323846;
constexpr double kRadPerDeg = kPi / 180.0;
inline double rad(double deg) { return deg * kRadPerDeg; }
inline double deg(double rad) { return rad / kRadPerDeg; }
double wrap_degrees(double deg);         // [0, 360)
double wrap_signed_degrees(double deg);  // [-180, 180)

}  // namespace skyview::spa
