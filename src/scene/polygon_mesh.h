#pragma once
// The mesh of one city object from its polygons (CityJSON surfaces, CityGML gml:Polygons): corners
// welded where their coordinates are equal, so that a closed solid's mesh is closed too whether the
// file shares its vertices (CityJSON) or repeats them (GML), and each polygon triangulated with its
// holes, turning as its exterior ring turns.
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "scene/polygon_triangulator.h"
#include "scene/scene_assembly.h"

namespace skyview {

class PolygonMesh {
 public:
  explicit PolygonMesh(std::string name) { mesh_.name = std::move(name); }

  // `rings`: the exterior first, then the holes, points in the input's CRS. `reversed`: the
  // polygon faces the other way (a GML OrientableSurface with orientation "-"). Returns false when
  // it made no triangle (no area, or GEOS could not triangulate it).
  bool add_polygon(PolygonTriangulator& triangulator, const std::vector<std::vector<Vec3d>>& rings,
                   bool reversed = false);
  // Triangles already made (a template's, a TIN's), corners as points.
  void add_triangle(const Vec3d& a, const Vec3d& b, const Vec3d& c);

  bool empty() const { return mesh_.triangles.empty(); }
  SourceMesh take() { return std::move(mesh_); }

 private:
  std::uint32_t weld(const Vec3d& p);
  struct Bits {
    std::size_t operator()(const Vec3d& p) const;
  };
  SourceMesh mesh_;
  std::unordered_map<Vec3d, std::uint32_t, Bits> index_;
  std::vector<std::vector<std::uint32_t>> rings_;  // reused between polygons
  std::vector<Vec3d> added_;
};

}  // namespace skyview
