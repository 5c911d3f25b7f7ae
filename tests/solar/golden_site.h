#pragma once
// The SPA report's worked example site (Golden, Colorado; Reda & Andreas 2008, Table A5.1).
#include "skyview/solar/solar_position.h"

namespace skyview::test {

inline Site golden_site() {
  Site s;
  s.latitude_deg = 39.742476;
  s.longitude_deg = -105.1786;
  s.elevation_m = 1830.14;
  s.pressure_mbar = 820.0;
  s.temperature_c = 11.0;
  s.delta_t_s = 67.0;
  s.delta_ut1_s = 0.0;
  return s;
}

}  // namespace skyview::test
