#pragma once
// Arctangent of a slope without a library call, so loops that turn a row of slopes into angles
// vectorise; std::atan was a fifth of the sweep's time. Octant reduction to |r| <= tan(pi/8)
// (as in Cephes' atan), then a degree-6 polynomial in r^2 fitted here by least squares on
// Chebyshev nodes (numpy); the largest error over all reals is below 1e-11 rad, far below a
// float angle's rounding.
#include <cmath>

namespace skyview::detail {

inline double fast_atan(double s) {
  constexpr double kTan3Pi8 = 2.414213562373095, kTanPi8 = 0.41421356237309503;
  constexpr double kPi2 = 1.5707963267948966, kPi4 = 0.78539816339744831;
  const double x = std::abs(s);
  const bool big = x > kTan3Pi8, mid = x > kTanPi8;
  // Every candidate computed, then selected, and one division (x / 1 is exact): a loop over slopes
  // vectorises, where arithmetic under a branch would not (it could trap).
  const double below = x - 1.0, above = x + 1.0;
  const double r = (big ? -1.0 : (mid ? below : x)) / (big ? x : (mid ? above : 1.0));
  const double base = big ? kPi2 : (mid ? kPi4 : 0.0);
  const double z = r * r;
  const double p = 0.99999999999135447 +
                   z * (-0.33333332425428841 +
                        z * (0.19999902374476486 +
                             z * (-0.14282002999724588 +
                                  z * (0.11044828804060719 + z * (-0.084775623551893164 + z * 0.047472939178350347)))));
  return std::copysign(base + r * p, s);
}

}  // namespace skyview::detail
