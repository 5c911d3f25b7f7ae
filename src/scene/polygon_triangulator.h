#pragma once
// Triangles of planar polygons with holes (a CityJSON or CityGML surface, a footprint's roof), by
// GEOS's constrained Delaunay triangulation (GEOS >= 3.10: ear clipping of the polygon with its
// holes joined in, then Delaunay edge flips; no points added). A 3-D polygon is projected onto the
// plane of its exterior ring (its Newell normal), triangulated there, and its triangles index the
// original 3-D points, so that a surface's corners stay shared with its neighbours'. A ring that
// crosses itself is mended by GEOS's MakeValid first; the points that adds are lifted back onto the
// plane.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "skyview/scene/scene.h"

namespace skyview {

class PolygonTriangulator {
 public:
  PolygonTriangulator();
  ~PolygonTriangulator();
  PolygonTriangulator(const PolygonTriangulator&) = delete;
  PolygonTriangulator& operator=(const PolygonTriangulator&) = delete;

  // `rings` index `points`: the exterior first, then the holes, each closed or not (a repeated
  // last point and consecutive repeats are dropped). Appends triangles that index `points` and,
  // past its end, `added` (points a self-crossing ring was cut at), each turning as the exterior
  // ring turns. Returns false, appending nothing, for a polygon without area (fewer than three
  // distinct points, all on a line) or one GEOS cannot triangulate; indices out of range are the
  // caller's to prevent.
  bool triangulate(const std::vector<Vec3d>& points, const std::vector<std::vector<std::uint32_t>>& rings,
                   std::vector<std::array<std::uint32_t, 3>>& triangles, std::vector<Vec3d>& added);

 private:
  struct Geos;
  std::unique_ptr<Geos> geos_;
};

}  // namespace skyview
