#pragma once
// Analytic and synthetic height fields, defined on true ground positions (metres east and
// north of the raster centre) and rasterised onto any georeferenced grid. Tests use the
// analytic ones (canyon, pit, plane) with known sky-view factors; the sample-data script
// writes the synthetic city and mountains into sample_dems/.
#include <cstdint>
#include <functional>
#include <string>

#include "skyview/raster/terrain.h"

namespace skyview {

using HeightFunction = std::function<double(double east, double north)>;

// A north-up grid without CRS (metres) whose centre cell's centre is at (0, 0); needs odd sizes
// for that cell to exist.
GeoReference local_grid(int width, int height, double cell);

// Samples `f` at every cell centre. With a CRS, ground positions come from GeographicLib's
// local tangent plane at the raster centre, so the same function gives the same terrain in
// UTM and in degrees.
Terrain rasterize(const HeightFunction& f, int width, int height, const GeoReference& georef, double base = 0.0);

// Floor at 0 for |east| < width/2, walls of `height` beyond: an infinite street canyon along north.
HeightFunction street_canyon(double width, double height);
// A circular pit of `radius` and `depth` in a plane at 0.
HeightFunction circular_pit(double radius, double depth);
// An infinite plane of `slope` (radians) falling towards azimuth `aspect` (radians from north).
HeightFunction tilted_plane(double slope, double aspect);
// Street canyons, courtyard blocks, towers and a pit on a 1 m grid around the centre.
HeightFunction synthetic_city(std::uint64_t seed = 1);
// Ridges, valleys and peaks over a few kilometres.
HeightFunction synthetic_mountains(std::uint64_t seed = 1);

}  // namespace skyview
