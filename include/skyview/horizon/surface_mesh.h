#pragma once
// The surface every horizon method reads, as the triangles of the ray-cast reference: over cell
// centres, each quad of four valid centres split along its lower diagonal (so the crease is a
// valley and along any straight line the surface peaks on the grid lines, where the march and the
// sweep sample it), a quad with one nodata corner kept as the triangle of the other three, and any
// other quad left open (nodata never occludes). Skirts hang from every edge that only one triangle
// holds, so that a ray running exactly along such an edge still meets it (Embree's watertight test
// counts hits on an edge only where two triangles share it).
#include <cmath>
#include <cstddef>
#include <vector>

#include "skyview/raster/terrain.h"

namespace skyview {

// How far out over the open side a skirt's bottom lies, in cells.
constexpr double kSkirtOut = 0.01;

struct SurfaceMesh {
  // Vertex i below the terrain's width * height is cell (i % width, i / width) at its own height;
  // the rest are the skirts' bottom vertices, skirt_vertices[i - width * height].
  struct SkirtVertex {
    double col, row;  // pixel position in the terrain's buffer
    float z;          // height, in the terrain's own sign
  };
  std::vector<unsigned> triangles;  // three vertex indices each: the surface's first, then the skirts'
  std::size_t surface_triangles = 0;
  std::vector<SkirtVertex> skirt_vertices;
};

// Whether the quad of cells a = (c, r), b = (c + 1, r), d = (c, r + 1), e = (c + 1, r + 1) (heights,
// NaN for nodata) is split along a-e in the mesh of heights times `sign`: along its lower diagonal,
// or, with one nodata corner, along the diagonal that leaves the three valid corners a triangle.
inline bool quad_splits_along_ae(double za, double zb, double zd, double ze, double sign) {
  if (std::isnan(za) || std::isnan(ze)) return false;
  if (std::isnan(zb) || std::isnan(zd)) return true;
  return sign * (za + ze) <= sign * (zb + zd);
}

// The mesh's height (in the terrain's own sign: heights, not heights times `sign`) at pixel
// position (x, y) inside the buffer, from the triangle holding it as surface_mesh splits its quad
// (in a half quad, the valid triangle's); along a grid line only its two ends count. NaN where that
// triangle has a nodata corner.
double surface_height(const Terrain& terrain, double x, double y, double sign = 1.0);

// The mesh of `terrain`'s heights times `sign` (-1: the lowest angles' negated heights, whose quads
// may split along the other diagonal and whose skirts hang upwards), its skirts hanging
// `skirt_drop` (height units) below their edges, kSkirtOut of a cell out.
SurfaceMesh surface_mesh(const Terrain& terrain, double sign, double skirt_drop);

}  // namespace skyview
