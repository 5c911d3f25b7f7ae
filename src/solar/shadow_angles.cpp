// Shadow angles of a vertical façade (Olgyay's shading-mask angles, as in the hybrid
// shadow maps paper): the profile angle VSA is what an overhang's depth is designed against.
#include "skyview/solar/shadow_angles.h"

#include <cmath>
#include <limits>

#include "spa_geocentric.h"

namespace skyview {

ShadowAngles shadow_angles(double sun_azimuth_deg, double sun_elevation_deg, double facade_azimuth_deg) {
  ShadowAngles s;
  s.horizontal_deg = spa::wrap_signed_degrees(sun_azimuth_deg - facade_azimuth_deg);
  const double cos_hsa = std::cos(spa::rad(s.horizontal_deg));
  // Behind the façade (|HSA| >= 90) the profile angle is undefined: no direct sun on it.
  s.vertical_deg = cos_hsa > 1e-12 ? spa::deg(std::atan(std::tan(spa::rad(sun_elevation_deg)) / cos_hsa))
                                   : std::numeric_limits<double>::quiet_NaN();
  s.sun_on_facade = cos_hsa > 1e-12 && sun_elevation_deg > 0.0;
  return s;
}

}  // namespace skyview
