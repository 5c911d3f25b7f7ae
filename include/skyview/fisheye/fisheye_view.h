#pragma once
// `skyview fisheye`: the hemisphere an observer sees from a point at a height above a DSM, drawn as
// an upward-looking fish-eye camera would photograph it (projection.h for the projections and the
// orientation): sky in Preetham colour for a sun position (or a plain gradient), terrain and
// buildings shaded by their distance, the horizon line, and the binary sky mask beside it (255 =
// sky) that `skyview fisheye-svf` reads. The horizons come from the march along the observer's own
// rays in at least one direction per pixel of the rim (point_horizons.h).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "skyview/fisheye/projection.h"
#include "skyview/horizon/point_horizons.h"
#include "skyview/raster/terrain.h"

namespace skyview {

struct SunForView {
  double zenith = 0, azimuth = 0;  // radians, azimuth clockwise from north
  double turbidity = 3.0;
};

struct FisheyeViewOptions {
  int size = 1024;  // image width and height; the 90° circle is inscribed in it
  Projection projection = Projection::equidistant;
  bool mirror = false;
  std::optional<SunForView> sun;  // Preetham sky; none: a plain sky
  // Directions of the horizon: 0 chooses the smallest power of two at or above one per pixel of
  // the rim (π size), at least 64.
  int directions = 0;
  // The rest of the horizon options (radius, curvature, azimuth origin, method must be march).
  PointHorizonOptions horizons;
  bool annotate = true;  // horizon line, compass letters, svf and parameters printed on the picture
};

struct FisheyeView {
  int size = 0;
  std::vector<std::uint8_t> rgb;   // size * size * 3, rows top to bottom
  std::vector<std::uint8_t> mask;  // size * size, 255 = sky within the 90° circle, 0 elsewhere
  FisheyeFrame frame;
  PointHorizons horizons;  // of the one observer, in `directions` sectors
  PointSkyView values;     // from those horizons
  std::string problem;     // the observer's (then nothing is drawn)
};

// Throws skyview::Error for options out of range (size 64..8192, a radius, a method other than
// march); an observer outside the raster or on nodata gives a view with `problem` set.
FisheyeView fisheye_view(const Terrain& terrain, const Observer& observer, const FisheyeViewOptions& options);

}  // namespace skyview
