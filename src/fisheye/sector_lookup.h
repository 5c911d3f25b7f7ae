#pragma once
// The sector of n uniform sectors (sector 0 centred on `rotation`) that holds an azimuth: pictures
// draw each direction's horizon over its whole sector, as the svf sums count it.
#include <cmath>

namespace skyview::detail {

inline int sector_of(double azimuth, double rotation, int n) {
  const double turns = (azimuth - rotation) / (2.0 * M_PI) * n;
  int k = static_cast<int>(std::lround(turns)) % n;
  return k < 0 ? k + n : k;
}

}  // namespace skyview::detail
