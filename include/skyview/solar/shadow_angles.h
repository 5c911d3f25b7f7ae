#pragma once
// Horizontal and vertical shadow angles of a façade, as used for shading design and in
// "hybrid shadow maps" (Eqs. 1-2): HSA = sun azimuth - façade azimuth, VSA = atan(tan e / cos HSA).

namespace skyview {

struct ShadowAngles {
  double horizontal_deg = 0;   // HSA in [-180, 180): positive when the sun is clockwise of the normal
  double vertical_deg = 0;     // VSA, the sun's altitude seen in the plane of the façade normal; NaN when behind
  bool sun_on_facade = false;  // the sun is above the horizon and in front of the façade (|HSA| < 90)
};

// `facade_azimuth_deg` is the direction the façade faces (its outward normal), clockwise from
// north; sun azimuth clockwise from north and elevation (refracted) as from solar_position().
ShadowAngles shadow_angles(double sun_azimuth_deg, double sun_elevation_deg, double facade_azimuth_deg);

}  // namespace skyview
