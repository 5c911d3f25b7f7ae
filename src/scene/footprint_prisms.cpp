// Building footprints (any OGR polygon layer, read as skyview dsm reads them: FootprintLayer)
// extruded to closed prisms: walls, a flat roof and a floor, holes (courtyards) kept. The prism
// stands on the lowest ground along its outline (a DSM/DEM input of the same scene), else on 0 m.
#include <algorithm>
#include <cmath>
#include <limits>

#include "dsm/footprint_layer.h"
#include "scene/polygon_triangulator.h"
#include "scene/scene_input.h"
#include "skyview/core/error.h"

namespace skyview {
namespace {

constexpr double kGroundStep = 0.5;  // metres between ground samples along an outline

// The polygons of a footprint (MakeValid may have made a collection with lines in it).
void collect_polygons(const OGRGeometry* g, std::vector<const OGRPolygon*>& out) {
  const OGRwkbGeometryType type = wkbFlatten(g->getGeometryType());
  if (type == wkbPolygon) {
    out.push_back(g->toPolygon());
  } else if (type == wkbMultiPolygon || type == wkbGeometryCollection) {
    for (const OGRGeometry* part : *g->toGeometryCollection()) collect_polygons(part, out);
  }
}

// A ring's points without the closing one and consecutive repeats, turning counter-clockwise
// (seen from above) when `outer`, clockwise when a hole: walls then face out of the solid.
std::vector<Vec3d> ring_points(const OGRLinearRing& ring, bool outer) {
  std::vector<Vec3d> p;
  for (int i = 0; i < ring.getNumPoints(); ++i) {
    const Vec3d q{ring.getX(i), ring.getY(i), 0.0};
    if (p.empty() || p.back()[0] != q[0] || p.back()[1] != q[1]) p.push_back(q);
  }
  while (p.size() > 1 && p.front()[0] == p.back()[0] && p.front()[1] == p.back()[1]) p.pop_back();
  double twice_area = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const Vec3d &a = p[k], &b = p[(k + 1) % p.size()];
    twice_area += a[0] * b[1] - b[0] * a[1];
  }
  if ((twice_area > 0) != outer) std::reverse(p.begin(), p.end());
  return p;
}

class FootprintInput : public SceneInput {
 public:
  FootprintInput(const std::string& path, const SceneLoadOptions& o)
      : layer_(path, FootprintFields{o.height_field, o.base_field, o.absolute_heights, o.footprint_z_scale}),
        absolute_(o.absolute_heights) {
    if (o.height_field.empty()) {
      throw Error("'" + path + "' is a footprint layer: give --height-field, the field of its buildings' heights");
    }
  }

  std::string format() const override { return "footprints (" + layer_.driver_name() + ")"; }

  std::string declared_crs() const override {
    if (!layer_.crs()) return "";
    char* wkt = nullptr;
    layer_.crs()->exportToWkt(&wkt);
    std::string s = wkt ? wkt : "";
    CPLFree(wkt);
    return s;
  }

  std::optional<std::array<Vec3d, 2>> extent() const override {
    OGREnvelope e;
    if (layer_.layer().GetExtent(&e, TRUE) != OGRERR_NONE || !(e.MaxX >= e.MinX)) return std::nullopt;
    return std::array<Vec3d, 2>{Vec3d{e.MinX, e.MinY, 0}, Vec3d{e.MaxX, e.MaxY, 0}};
  }

  void add_to(SceneAssembly& scene) override {
    FootprintCounts counts;
    std::int64_t on_zero = 0;
    PolygonTriangulator triangulator;
    layer_.read(
        scene.to_scene(),
        [&](Footprint& f) {
          const std::string name = "footprint " + std::to_string(f.fid);
          std::vector<const OGRPolygon*> polygons;
          collect_polygons(f.polygons.get(), polygons);
          // The ground: the lowest along the outlines, where a DSM/DEM input covers them.
          double ground = std::numeric_limits<double>::quiet_NaN();
          if (std::isnan(f.base)) {
            std::vector<Vec3d> outline;
            for (const OGRPolygon* p : polygons) densify(*p->getExteriorRing(), outline);
            ground = scene.lowest_ground(outline);
          }
          const bool base_known = !std::isnan(f.base), on_sea_level = !base_known && std::isnan(ground);
          if (on_sea_level) ground = 0.0;
          const double top = footprint_top(f.height, f.base, absolute_, ground);
          const double bottom = base_known ? f.base : ground;
          if (std::isnan(top)) {
            scene.skip(name, "without a height");
            return;
          }
          if (!(top > bottom)) {
            scene.skip(name, "with its top not above its bottom");
            return;
          }
          on_zero += on_sea_level;
          SourceMesh mesh;
          mesh.name = name;
          std::int64_t flat = 0;
          for (const OGRPolygon* p : polygons) flat += !extrude(*p, bottom, top, triangulator, mesh);
          if (flat > 0) scene.drop_surfaces(flat, "roofs GEOS could not triangulate", name);
          scene.add(std::move(mesh), true);
        },
        counts);
    if (counts.polygons == 0) throw Error("'" + layer_.path() + "' holds no polygons");
    const std::string file = "'" + layer_.path() + "': ";
    if (on_zero > 0) {
      scene.warn(file + std::to_string(on_zero) + " footprints stand on 0 m: " +
                 (scene.has_ground() ? "no DSM/DEM input lies under them" : "no DSM/DEM input was given") +
                 " (give one, or --base-field)");
    }
    if (counts.not_polygons > 0) {
      scene.warn(file + std::to_string(counts.not_polygons) + " features are not polygons and were left out");
    }
    if (counts.repaired > 0) {
      scene.warn(file + std::to_string(counts.repaired) + " invalid footprints were mended by MakeValid");
    }
    if (const std::string w = geos_notices_warning(counts, layer_.path()); !w.empty()) scene.warn(w);
    for (int k = 0; k < counts.skipped; ++k)
      scene.skip("", "invalid beyond repair, of no area, or off the scene's CRS");
  }

 private:
  // Points along a ring every kGroundStep metres (its corners included), for the ground under it.
  static void densify(const OGRLinearRing& ring, std::vector<Vec3d>& out) {
    for (int i = 0; i + 1 < ring.getNumPoints(); ++i) {
      const double x0 = ring.getX(i), y0 = ring.getY(i), x1 = ring.getX(i + 1), y1 = ring.getY(i + 1);
      const int steps = std::max(1, static_cast<int>(std::ceil(std::hypot(x1 - x0, y1 - y0) / kGroundStep)));
      for (int s = 0; s < steps && s < 100000; ++s) {
        const double t = static_cast<double>(s) / steps;
        out.push_back({x0 + t * (x1 - x0), y0 + t * (y1 - y0), 0.0});
      }
    }
  }

  // Appends one polygon's prism to `mesh`: walls from every ring edge, the roof triangulated with
  // its holes at `top`, the same triangles turned down as the floor at `bottom`. Returns false
  // (walls kept) where the roof could not be triangulated.
  static bool extrude(const OGRPolygon& polygon, double bottom, double top, PolygonTriangulator& triangulator,
                      SourceMesh& mesh) {
    std::vector<std::vector<Vec3d>> rings;
    if (!polygon.getExteriorRing()) return false;
    rings.push_back(ring_points(*polygon.getExteriorRing(), true));
    for (int h = 0; h < polygon.getNumInteriorRings(); ++h)
      rings.push_back(ring_points(*polygon.getInteriorRing(h), false));
    // Roof corners first (the triangulator indexes them), each followed in `floor_of` by its floor twin.
    std::vector<Vec3d> roof;
    std::vector<std::vector<std::uint32_t>> roof_rings;
    for (const auto& r : rings) {
      roof_rings.emplace_back();
      for (const Vec3d& p : r) {
        roof_rings.back().push_back(static_cast<std::uint32_t>(roof.size()));
        roof.push_back({p[0], p[1], top});
      }
    }
    std::vector<std::array<std::uint32_t, 3>> tri;
    std::vector<Vec3d> added;
    const bool roofed = !rings[0].empty() && triangulator.triangulate(roof, roof_rings, tri, added);
    for (const Vec3d& a : added) roof.push_back({a[0], a[1], top});
    const std::uint32_t base = static_cast<std::uint32_t>(mesh.vertices.size());
    const std::uint32_t n = static_cast<std::uint32_t>(roof.size());
    for (const Vec3d& p : roof) mesh.vertices.push_back(p);                     // top: base + i
    for (const Vec3d& p : roof) mesh.vertices.push_back({p[0], p[1], bottom});  // bottom: base + n + i
    for (const auto& r : roof_rings) {
      for (std::size_t k = 0; k < r.size(); ++k) {
        const std::uint32_t a = r[k], b = r[(k + 1) % r.size()];
        mesh.triangles.push_back({base + n + a, base + n + b, base + b});
        mesh.triangles.push_back({base + n + a, base + b, base + a});
      }
    }
    for (const auto& t : tri) {
      mesh.triangles.push_back({base + t[0], base + t[1], base + t[2]});
      mesh.triangles.push_back({base + n + t[0], base + n + t[2], base + n + t[1]});
    }
    return roofed;
  }

  mutable FootprintLayer layer_;
  bool absolute_;
};

}  // namespace

std::unique_ptr<SceneInput> open_footprints(const std::string& path, const SceneLoadOptions& options) {
  return std::make_unique<FootprintInput>(path, options);
}

}  // namespace skyview
