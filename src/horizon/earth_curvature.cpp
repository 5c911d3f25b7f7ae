#include "earth_curvature.h"

#include <cmath>

#include "ray_scan.h"
#include "skyview/core/error.h"

namespace skyview::detail {

double curvature_coefficient(const HorizonParams& params, double max_distance, double earth_radius) {
  if (!(params.refraction >= 0.0 && params.refraction < 1.0)) throw UsageError("--refraction must be in [0, 1)");
  const double c = (1.0 - params.refraction) / (2.0 * earth_radius);
  if (params.curvature == "off") return 0.0;
  if (params.curvature == "on") return c;
  if (params.curvature != "auto") throw UsageError("--curvature must be auto, on or off");
  // The drop changes the elevation angle at distance d by about c*d radians.
  const double threshold = 0.01 * M_PI / 180.0;
  return c * max_distance > threshold ? c : 0.0;
}

ScanSettings scan_settings(const HorizonParams& p, const Terrain& terrain) {
  ScanSettings s;
  s.directions = p.directions;
  s.lower = p.lower;
  s.early_exit = p.early_exit;
  s.seed = p.seed;
  s.max_distance = p.radius;
  s.curvature = curvature_coefficient(p, p.radius, terrain.frame.earth_radius());
  return s;
}

}  // namespace skyview::detail
