#include "skyview/horizon/surface_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace skyview {
namespace {

// A skirt hangs from every edge of the mesh that only one triangle holds (the raster's sides, the rims
// of nodata holes and the open diagonal of a half quad), kSkirtOut of a cell outward and ten cells
// down. A ray running exactly along such an edge meets the mesh on it, and Embree's watertight test
// only counts hits on edges that two triangles share: without skirts a wall one cell in from the
// raster's corner was missed (1.4 rad off), and a ray along a grid line beside a hole lost its hit
// on the hole's rim (0.36 rad). Hanging below the edge, a skirt hides nothing from a ray that passes
// above it, but a ray that then falls steeply enough to catch up with its 1000:1 lean: within 0.06
// degrees of the nadir across the edge, more than 10 degrees down where its course is within 0.01
// degrees of the edge's. A deeper skirt (10 km) was too thin for float intersections and blocked
// rays just above the boundary.
//
// Appends the skirts' triangles to `idx` (indices past the grid's vertices count into the returned
// skirt vertices). Neighbouring edges that face the same way share their skirt's vertices, so that a
// skirt is itself watertight along the edge.
std::vector<SurfaceMesh::SkirtVertex> hang_skirts(const Terrain& t, double sign, double drop,
                                                  std::vector<unsigned>& idx) {
  const int w = t.width(), h = t.height();
  const std::size_t grid = static_cast<std::size_t>(w) * h;
  auto quad_has_triangles = [&](int c, int r) {  // quad (c, r) spans cells c..c+1, r..r+1
    if (c < 0 || r < 0 || c + 1 >= w || r + 1 >= h) return false;
    return t.valid(c, r) + t.valid(c + 1, r) + t.valid(c, r + 1) + t.valid(c + 1, r + 1) >= 3;
  };
  std::vector<SurfaceMesh::SkirtVertex> skirt;
  std::unordered_map<std::uint64_t, unsigned> made;  // (grid vertex, outward direction) -> vertex
  auto skirt_vertex = [&](int c, int r, int out_c, int out_r) {
    const std::uint64_t key = t.heights.index(c, r) * 9 + static_cast<std::uint64_t>(3 * (out_c + 1) + (out_r + 1));
    const auto [at, fresh] = made.try_emplace(key, static_cast<unsigned>(grid + skirt.size()));
    if (fresh) {
      const double step = kSkirtOut / std::hypot(out_c, out_r);
      skirt.push_back({c + out_c * step, r + out_r * step, static_cast<float>(t.heights(c, r) - sign * drop)});
    }
    return at->second;
  };
  // The edge from cell (c0, r0) to (c1, r1), open towards (out_c, out_r).
  auto hang = [&](int c0, int r0, int c1, int r1, int out_c, int out_r) {
    const unsigned p = static_cast<unsigned>(t.heights.index(c0, r0)),
                   q = static_cast<unsigned>(t.heights.index(c1, r1));
    const unsigned p_out = skirt_vertex(c0, r0, out_c, out_r), q_out = skirt_vertex(c1, r1, out_c, out_r);
    idx.insert(idx.end(), {p, q, q_out, p, q_out, p_out});
  };
  // A grid line's edge between two valid cells belongs to each quad beside it that has triangles.
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c + 1 < w; ++c) {
      if (!t.valid(c, r) || !t.valid(c + 1, r)) continue;
      const bool above = quad_has_triangles(c, r - 1), below = quad_has_triangles(c, r);
      if (above != below) hang(c, r, c + 1, r, 0, above ? 1 : -1);
    }
  }
  for (int c = 0; c < w; ++c) {
    for (int r = 0; r + 1 < h; ++r) {
      if (!t.valid(c, r) || !t.valid(c, r + 1)) continue;
      const bool left = quad_has_triangles(c - 1, r), right = quad_has_triangles(c, r);
      if (left != right) hang(c, r, c, r + 1, left ? 1 : -1, 0);
    }
  }
  // A half quad's diagonal, open towards its nodata corner.
  for (int r = 0; r + 1 < h; ++r) {
    for (int c = 0; c + 1 < w; ++c) {
      const bool va = t.valid(c, r), vb = t.valid(c + 1, r), vd = t.valid(c, r + 1), ve = t.valid(c + 1, r + 1);
      if (va + vb + vd + ve != 3) continue;
      if (!va) hang(c + 1, r, c, r + 1, -1, -1);
      if (!vb) hang(c, r, c + 1, r + 1, 1, -1);
      if (!vd) hang(c, r, c + 1, r + 1, -1, 1);
      if (!ve) hang(c + 1, r, c, r + 1, 1, 1);
    }
  }
  return skirt;
}

}  // namespace

SurfaceMesh surface_mesh(const Terrain& t, double sign, double skirt_drop) {
  const int w = t.width(), h = t.height();
  SurfaceMesh mesh;
  std::vector<unsigned>& idx = mesh.triangles;
  idx.reserve(static_cast<std::size_t>(w) * h * 6);
  for (int r = 0; r + 1 < h; ++r) {
    for (int c = 0; c + 1 < w; ++c) {
      const unsigned a = static_cast<unsigned>(t.heights.index(c, r)), b = a + 1;
      const unsigned d = static_cast<unsigned>(t.heights.index(c, r + 1)), e = d + 1;
      const bool va = t.valid(c, r), vb = t.valid(c + 1, r), vd = t.valid(c, r + 1), ve = t.valid(c + 1, r + 1);
      const int valid = va + vb + vd + ve;
      if (valid == 4) {
        // Split along the lower diagonal (in this mesh's sign): the crease is a valley.
        if (quad_splits_along_ae(t.heights(c, r), t.heights(c + 1, r), t.heights(c, r + 1), t.heights(c + 1, r + 1),
                                 sign)) {
          idx.insert(idx.end(), {a, b, e, a, e, d});
        } else {
          idx.insert(idx.end(), {a, b, d, b, e, d});
        }
      } else if (valid == 3) {  // the valid half
        if (!va) idx.insert(idx.end(), {b, e, d});
        if (!vb) idx.insert(idx.end(), {a, e, d});
        if (!vd) idx.insert(idx.end(), {a, b, e});
        if (!ve) idx.insert(idx.end(), {a, b, d});
      }
    }
  }
  mesh.surface_triangles = idx.size() / 3;
  mesh.skirt_vertices = hang_skirts(t, sign, skirt_drop, idx);
  return mesh;
}

double surface_height(const Terrain& t, double x, double y, double sign) {
  const int x0 = std::min(static_cast<int>(x), std::max(0, t.width() - 2));
  const int y0 = std::min(static_cast<int>(y), std::max(0, t.height() - 2));
  const double fx = x - x0, fy = y - y0;
  const int x1 = std::min(x0 + 1, t.width() - 1), y1 = std::min(y0 + 1, t.height() - 1);
  const double za = t.heights(x0, y0), zb = t.heights(x1, y0), zd = t.heights(x0, y1), ze = t.heights(x1, y1);
  // Along a grid line only its two ends count.
  if (fy == 0.0) return fx == 0.0 ? za : za + fx * (zb - za);
  if (fx == 0.0) return za + fy * (zd - za);
  if (quad_splits_along_ae(za, zb, zd, ze, sign)) {
    return fx >= fy ? za + fx * (zb - za) + fy * (ze - zb) : za + fy * (zd - za) + fx * (ze - zd);
  }
  return fx + fy <= 1.0 ? za + fx * (zb - za) + fy * (zd - za) : ze + (1 - fx) * (zd - ze) + (1 - fy) * (zb - ze);
}

}  // namespace skyview
