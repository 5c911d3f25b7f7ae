#pragma once
// The sweep's near field (sweep.cpp): the first steps of every cell's own ray read exactly, in
// vector blocks along a row, and the angles written into a direction's plane.
#include <vector>

#include "horizon/sweep_geometry.h"

namespace skyview::detail::sweep {

// The highest slope of each cell [a, b) of the row at `major` over `crossings` into best[a, b)
// (indexed by minor) and, where `lowest` is not null, minus the lowest slope into lowest[a, b).
void near_field(const SweepGeometry& g, const std::vector<NearCrossing>& crossings, int major, int a, int b,
                float* best, float* lowest);

// Angles of the cells [a, b) of the row at `major` into the direction's plane of the field
// (window-sized, row-major), turned in place in `best` first so that the arctangents run as one
// vector loop. Nothing ahead on either side (-inf) means open: terrain beyond the raster does not
// occlude. Nodata cells get NaN, as the field starts.
void write_angles(const SweepGeometry& g, const Window& window, int major, int a, int b, float* best, double sign,
                  float* plane);

}  // namespace skyview::detail::sweep
