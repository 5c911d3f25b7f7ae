#include "scene/polygon_mesh.h"

#include <cstring>

namespace skyview {

std::size_t PolygonMesh::Bits::operator()(const Vec3d& p) const {
  std::uint64_t h = 0;
  for (double c : p) {
    c = c == 0.0 ? 0.0 : c;  // -0 and 0 are one corner
    std::uint64_t b;
    std::memcpy(&b, &c, 8);
    h = (h ^ b) * 0x100000001B3ull + 0x9E3779B97F4A7C15ull;
  }
  return static_cast<std::size_t>(h ^ (h >> 29));
}

std::uint32_t PolygonMesh::weld(const Vec3d& p) {
  const auto [at, fresh] = index_.emplace(p, static_cast<std::uint32_t>(mesh_.vertices.size()));
  if (fresh) mesh_.vertices.push_back(p);
  return at->second;
}

bool PolygonMesh::add_polygon(PolygonTriangulator& triangulator, const std::vector<std::vector<Vec3d>>& rings,
                              bool reversed) {
  rings_.resize(rings.size());
  for (std::size_t r = 0; r < rings.size(); ++r) {
    rings_[r].clear();
    for (const Vec3d& p : rings[r]) rings_[r].push_back(weld(p));
  }
  added_.clear();
  const std::size_t first = mesh_.triangles.size();
  if (!triangulator.triangulate(mesh_.vertices, rings_, mesh_.triangles, added_)) return false;
  // Points the triangulator added (where a ring crossed itself) are new corners, welded like the rest.
  if (!added_.empty()) {
    const std::uint32_t past = static_cast<std::uint32_t>(mesh_.vertices.size());
    std::vector<std::uint32_t> index_of(added_.size());
    for (std::size_t k = 0; k < added_.size(); ++k) index_of[k] = weld(added_[k]);
    for (std::size_t t = first; t < mesh_.triangles.size(); ++t) {
      for (std::uint32_t& i : mesh_.triangles[t]) {
        if (i >= past) i = index_of[i - past];
      }
    }
  }
  if (reversed) {
    for (std::size_t t = first; t < mesh_.triangles.size(); ++t)
      std::swap(mesh_.triangles[t][1], mesh_.triangles[t][2]);
  }
  return true;
}

void PolygonMesh::add_triangle(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  mesh_.triangles.push_back({weld(a), weld(b), weld(c)});
}

}  // namespace skyview
