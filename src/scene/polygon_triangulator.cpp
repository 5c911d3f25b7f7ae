#include "scene/polygon_triangulator.h"

#include <geos_c.h>

#include <cmath>
#include <cstring>
#include <unordered_map>

namespace skyview {
namespace {

// A projected point's exact bits: GEOS copies input coordinates into its triangles unchanged.
struct PointKey {
  double u, v;
  bool operator==(const PointKey& o) const { return std::memcmp(this, &o, sizeof *this) == 0; }
};
struct PointKeyHash {
  std::size_t operator()(const PointKey& k) const {
    std::uint64_t a, b;
    std::memcpy(&a, &k.u, 8);
    std::memcpy(&b, &k.v, 8);
    return std::hash<std::uint64_t>()(a * 0x9E3779B97F4A7C15ull ^ b);
  }
};

Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3d& a, const Vec3d& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace

struct PolygonTriangulator::Geos {
  GEOSContextHandle_t h = GEOS_init_r();
  ~Geos() { GEOS_finish_r(h); }
  // GEOS's own geometry, freed on every path out.
  struct Ptr {
    GEOSContextHandle_t h;
    GEOSGeometry* g;
    ~Ptr() {
      if (g) GEOSGeom_destroy_r(h, g);
    }
  };
};

PolygonTriangulator::PolygonTriangulator() : geos_(std::make_unique<Geos>()) {
  // GEOS reports a failed triangulation by returning null; its message adds nothing for the user.
  GEOSContext_setErrorMessageHandler_r(
      geos_->h, [](const char*, void*) {}, nullptr);
  GEOSContext_setNoticeMessageHandler_r(
      geos_->h, [](const char*, void*) {}, nullptr);
}

PolygonTriangulator::~PolygonTriangulator() = default;

bool PolygonTriangulator::triangulate(const std::vector<Vec3d>& points,
                                      const std::vector<std::vector<std::uint32_t>>& rings,
                                      std::vector<std::array<std::uint32_t, 3>>& triangles, std::vector<Vec3d>& added) {
  // Rings without repeats: consecutive equal points and the closing point go.
  std::vector<std::vector<std::uint32_t>> clean;
  for (const auto& ring : rings) {
    std::vector<std::uint32_t> r;
    for (std::uint32_t i : ring) {
      const Vec3d& p = points[i];
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) return false;
      if (!r.empty() && points[r.back()] == points[i]) continue;
      r.push_back(i);
    }
    while (r.size() > 1 && points[r.front()] == points[r.back()]) r.pop_back();
    if (r.size() >= 3) {
      clean.push_back(std::move(r));
    } else if (clean.empty()) {
      return false;  // an exterior ring without area
    }
  }
  if (clean.empty()) return false;
  const std::vector<std::uint32_t>& outer = clean.front();
  const Vec3d p0 = points[outer.front()];
  // Newell's normal of the exterior ring: its direction is the ring's turning, its length twice its area.
  Vec3d n{0, 0, 0};
  for (std::size_t k = 0; k < outer.size(); ++k) {
    const Vec3d a = sub(points[outer[k]], p0), b = sub(points[outer[(k + 1) % outer.size()]], p0);
    n = {n[0] + (a[1] - b[1]) * (a[2] + b[2]), n[1] + (a[2] - b[2]) * (a[0] + b[0]),
         n[2] + (a[0] - b[0]) * (a[1] + b[1])};
  }
  const double length = std::sqrt(dot(n, n));
  if (!(length > 0) || !std::isfinite(length)) return false;
  n = {n[0] / length, n[1] / length, n[2] / length};
  if (clean.size() == 1 && outer.size() == 3) {  // most surfaces of a triangulated model
    triangles.push_back({outer[0], outer[1], outer[2]});
    return true;
  }
  if (clean.size() == 1 && outer.size() == 4) {  // walls: a convex quad splits along either diagonal
    bool convex = true;
    for (int k = 0; k < 4 && convex; ++k) {
      const Vec3d& a = points[outer[k]];
      const Vec3d& b = points[outer[(k + 1) % 4]];
      const Vec3d& c = points[outer[(k + 2) % 4]];
      convex = dot(cross(sub(b, a), sub(c, b)), n) > 0;
    }
    if (convex) {
      triangles.push_back({outer[0], outer[1], outer[2]});
      triangles.push_back({outer[0], outer[2], outer[3]});
      return true;
    }
  }
  // A right-handed frame (u, v, n): counter-clockwise in (u, v) turns as the exterior ring does.
  const int smallest = std::abs(n[0]) <= std::abs(n[1]) && std::abs(n[0]) <= std::abs(n[2]) ? 0
                       : std::abs(n[1]) <= std::abs(n[2])                                   ? 1
                                                                                            : 2;
  Vec3d axis{0, 0, 0};
  axis[smallest] = 1;
  Vec3d u = cross(n, axis);
  const double ul = std::sqrt(dot(u, u));
  u = {u[0] / ul, u[1] / ul, u[2] / ul};
  const Vec3d v = cross(n, u);

  GEOSContextHandle_t h = geos_->h;
  std::unordered_map<PointKey, std::uint32_t, PointKeyHash> index;
  std::vector<GEOSGeometry*> geos_rings;
  auto free_rings = [&] {
    for (GEOSGeometry* g : geos_rings) GEOSGeom_destroy_r(h, g);
  };
  for (const auto& ring : clean) {
    GEOSCoordSequence* seq = GEOSCoordSeq_create_r(h, static_cast<unsigned>(ring.size() + 1), 2);
    for (std::size_t k = 0; k <= ring.size(); ++k) {
      const std::uint32_t i = ring[k % ring.size()];
      const Vec3d d = sub(points[i], p0);
      const PointKey key{dot(d, u), dot(d, v)};
      index.emplace(key, i);
      GEOSCoordSeq_setXY_r(h, seq, static_cast<unsigned>(k), key.u, key.v);
    }
    GEOSGeometry* r = GEOSGeom_createLinearRing_r(h, seq);  // takes the sequence
    if (!r) {
      free_rings();
      return false;
    }
    geos_rings.push_back(r);
  }
  Geos::Ptr polygon{h, GEOSGeom_createPolygon_r(h, geos_rings[0], geos_rings.data() + 1,
                                                static_cast<unsigned>(geos_rings.size() - 1))};
  if (!polygon.g) return false;  // (GEOS owns the rings from the call on)
  Geos::Ptr valid{h, nullptr};
  const GEOSGeometry* input = polygon.g;
  if (GEOSisValid_r(h, polygon.g) != 1) {
    valid.g = GEOSMakeValid_r(h, polygon.g);
    if (!valid.g) return false;
    input = valid.g;
  }
  Geos::Ptr result{h, GEOSConstrainedDelaunayTriangulation_r(h, input)};
  if (!result.g) return false;
  const int count = GEOSGetNumGeometries_r(h, result.g);
  const std::size_t first = triangles.size();
  for (int t = 0; t < count; ++t) {
    const GEOSGeometry* tri = GEOSGetGeometryN_r(h, result.g, t);
    const GEOSGeometry* ring = tri ? GEOSGetExteriorRing_r(h, tri) : nullptr;
    const GEOSCoordSequence* seq = ring ? GEOSGeom_getCoordSeq_r(h, ring) : nullptr;
    unsigned size = 0;
    if (!seq || !GEOSCoordSeq_getSize_r(h, seq, &size) || size < 3) continue;
    std::array<std::uint32_t, 3> corner{};
    double uv[3][2];
    for (unsigned k = 0; k < 3; ++k) {
      GEOSCoordSeq_getXY_r(h, seq, k, &uv[k][0], &uv[k][1]);
      const PointKey key{uv[k][0], uv[k][1]};
      auto [at, fresh] = index.emplace(key, static_cast<std::uint32_t>(points.size() + added.size()));
      if (fresh) {
        added.push_back({p0[0] + key.u * u[0] + key.v * v[0], p0[1] + key.u * u[1] + key.v * v[1],
                         p0[2] + key.u * u[2] + key.v * v[2]});
      }
      corner[k] = at->second;
    }
    const double area = (uv[1][0] - uv[0][0]) * (uv[2][1] - uv[0][1]) - (uv[2][0] - uv[0][0]) * (uv[1][1] - uv[0][1]);
    if (area == 0) continue;
    if (area < 0) std::swap(corner[1], corner[2]);
    triangles.push_back(corner);
  }
  return triangles.size() > first;
}

}  // namespace skyview
