#pragma once
// Delta T = TT - UT1, the SPA's input that converts Universal Time to the ephemeris time at
// which the sun's ecliptic position is evaluated. An error of 10 s moves the sun ~1e-4 deg.

namespace skyview {

// Automatic Delta T (seconds) for a year with fraction, by this policy:
//  - 1950.0 .. 2020.1: the observed USNO table, linearly interpolated;
//  - after the table up to 2050: 69.2 s (TAI - UTC = 37 s since 2017 bounds it to 68.3..70.1 s
//    while leap seconds stay as they are; extrapolating the trend is not better);
//  - otherwise the Espenak & Meeus (2006) polynomials.
double automatic_delta_t_s(double decimal_year);

// The Espenak & Meeus (NASA, 2006) polynomial expressions alone (valid -1999 .. 3000,
// with the parabolic long-term extrapolation beyond).
double espenak_meeus_delta_t_s(double decimal_year);

}  // namespace skyview
