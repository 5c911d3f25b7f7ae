#pragma once
// Scenes of the shadow tests and benchmark: a ground square, boxes on it, and a DSM meshed as the
// ray cast meshes it (surface_mesh.h), with receivers on a grid.
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "skyview/horizon/surface_mesh.h"
#include "skyview/render/shadow_maps.h"
#include "skyview/scene/scene.h"

namespace skyview::test {

inline SceneMesh ground_square(float half) {
  return {"ground",
          "test",
          {{-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}},
          {{0, 1, 2}, {0, 2, 3}}};
}

// A closed box over [lo, hi].
inline SceneMesh box(const std::string& name, Vec3f lo, Vec3f hi) {
  SceneMesh m{name, "test", {}, {}};
  for (int i = 0; i < 8; ++i)
    m.vertices.push_back({i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]});
  // Two triangles per face, vertex index bits: x = 1, y = 2, z = 4.
  m.triangles = {{0, 3, 1}, {0, 2, 3}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                 {2, 7, 3}, {2, 6, 7}, {0, 6, 2}, {0, 4, 6}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

// The DSM's surface as one mesh, vertices at cell centres (x east, y north of the grid's origin).
inline SceneMesh dsm_mesh(const Terrain& t) {
  const SurfaceMesh sm = surface_mesh(t, 1.0, 10.0 * t.georef.geotransform[1]);
  SceneMesh m{"dsm", "test", {}, {}};
  const GeoReference& g = t.georef;
  const std::size_t grid = static_cast<std::size_t>(t.width()) * t.height();
  for (std::size_t i = 0; i < grid; ++i) {
    const double c = static_cast<double>(i % t.width()), r = static_cast<double>(i / t.width());
    m.vertices.push_back({static_cast<float>(g.x_of(c, r)), static_cast<float>(g.y_of(c, r)),
                          static_cast<float>(t.base_height + t.heights.values()[i])});
  }
  for (const SurfaceMesh::SkirtVertex& s : sm.skirt_vertices) {
    m.vertices.push_back({static_cast<float>(g.x_of(s.col, s.row)), static_cast<float>(g.y_of(s.col, s.row)),
                          static_cast<float>(t.base_height + s.z)});
  }
  for (std::size_t k = 0; k + 2 < sm.triangles.size(); k += 3) {
    m.triangles.push_back({sm.triangles[k], sm.triangles[k + 1], sm.triangles[k + 2]});
  }
  return m;
}

// Whether a cell and its eight neighbours have one height: a roof's or a street's inside, seen
// from above and facing straight up.
inline bool flat_cell(const Terrain& t, int c, int r, double tolerance = 0.01) {
  if (c < 1 || r < 1 || c + 1 >= t.width() || r + 1 >= t.height()) return false;
  const double z = t.heights(c, r);
  for (int dr = -1; dr <= 1; ++dr) {
    for (int dc = -1; dc <= 1; ++dc) {
      if (std::abs(t.heights(c + dc, r + dr) - z) > tolerance) return false;
    }
  }
  return true;
}

// Receivers at the centres of flat cells (every `step`-th cell), facing up.
inline ShadowReceivers flat_cell_receivers(const Terrain& t, int step) {
  ShadowReceivers out;
  const GeoReference& g = t.georef;
  for (int r = 0; r < t.height(); r += step) {
    for (int c = 0; c < t.width(); c += step) {
      if (!flat_cell(t, c, r)) continue;
      out.points.push_back({static_cast<float>(g.x_of(c, r)), static_cast<float>(g.y_of(c, r)),
                            static_cast<float>(t.base_height + t.heights(c, r))});
      out.normals.push_back({0, 0, 1});
    }
  }
  return out;
}

}  // namespace skyview::test
