#pragma once
// Horizons of observers at any point of a raster, at a height above its surface: what a field
// climatologist's fish-eye camera sees 1.1 m above a street, not what the street's cell sees from
// the surface. Each observer's horizons are found exactly along its own rays by the walk the raster
// methods share (every row and column crossing of the one surface mesh, src/horizon/ray_scan.h), or
// by the Embree ray cast on that mesh (the reference), never by reading a raster of results.
#include <cstddef>
#include <string>
#include <vector>

#include "skyview/core/progress.h"
#include "skyview/horizon/horizon_engine.h"
#include "skyview/raster/terrain.h"

namespace skyview {

// An observer: a pixel position in the terrain (cell centres at whole numbers, so GDAL's
// pixel/line coordinate minus 0.5) and its eye's height above the surface there, in metres.
struct Observer {
  double col = 0, row = 0;
  double height = 1.1;
};

// One step up of the steepest slope seen along a direction: from `distance` (metres, along the
// ground) on, terrain is seen up to `slope` (rise over run, Earth's curvature included). A ray at
// elevation atan(s) meets the terrain first at the first step whose slope is at least s.
struct RisingStep {
  float distance, slope;
};

struct PointHorizonOptions {
  // directions (uniform sectors), radius (0: to the raster's edge), curvature, refraction,
  // azimuth_origin and early_exit are used; the rest (samples, far lines, seed, rays, lower, grid
  // lines) belong to the raster methods and must keep their defaults.
  HorizonParams params;
  // "march": every row and column crossing along each observer's own rays (exact on the mesh);
  // "raycast": Embree rays bracketed to 1e-5 rad (the reference; no curvature).
  std::string method = "march";
  bool rising_steps = false;  // keep each direction's RisingSteps (march only; fish-eye pictures)
};

struct PointHorizons {
  int directions = 0;
  double sector_rotation = 0;  // azimuth of sector 0 (radians, clockwise from true north)
  double curvature = 0;        // c of drop = c d² applied (0: off)
  double reach = 0;            // metres a ray may run (the radius, or the raster's diagonal)
  // Radians above the horizontal, [observer * directions + k]; NaN for an observer with a problem.
  std::vector<float> upper;
  // Per observer: empty, or why it has no horizons ("outside the raster", "on nodata").
  std::vector<std::string> problem;
  // Per observer: the surface's absolute height under it (metres) and its eye's; NaN with a problem.
  std::vector<double> ground, eye;
  // [observer][direction], with PointHorizonOptions::rising_steps.
  std::vector<std::vector<std::vector<RisingStep>>> rising;

  const float* of(std::size_t observer) const { return upper.data() + observer * directions; }
  double azimuth(int k) const { return sector_rotation + sector_azimuth(k, directions); }
};

// Throws skyview::Error for options out of range (directions 1..65536, a negative or infinite
// radius, an unknown method, curvature with the ray cast, a negative height) before any work;
// observers outside the raster or over nodata get a problem, and the others are computed.
PointHorizons point_horizons(const Terrain& terrain, const std::vector<Observer>& observers,
                             const PointHorizonOptions& options, ProgressCounter* progress = nullptr);

// What `skyview points` reports of an observer, from its horizons (n uniform sectors turned by
// `rotation`): svf and sky_visibility of a horizontal surface at the eye (sky_view.h), and
// svf_surface, the view factor of a surface at the eye tilted as the ground under it is (Horn's
// slope and aspect of the nearest cell).
struct PointSkyView {
  double svf = 0, svf_surface = 0, sky_visibility = 0;
};
PointSkyView point_sky_view(const Terrain& terrain, const Observer& observer, const float* horizons, int n,
                            double rotation);

}  // namespace skyview
