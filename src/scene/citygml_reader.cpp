// CityGML 1.0 and 2.0 (LoD1-LoD3, and LoD4 where present) through libcitygml: each top-level city
// object (a Building with its thematic surfaces, parts and installations) becomes one mesh of its
// polygons at the chosen level of detail, implicit geometries placed by their matrices. Polygons are
// triangulated here (PolygonTriangulator), not by libcitygml's GLU tesselator, so that their corners
// are shared with neighbouring polygons as in every other reader.
#include <citygml/citygml.h>
#include <citygml/citygmllogger.h>
#include <citygml/citymodel.h>
#include <citygml/cityobject.h>
#include <citygml/envelope.h>
#include <citygml/geometry.h>
#include <citygml/implictgeometry.h>
#include <citygml/linearring.h>
#include <citygml/polygon.h>
#include <citygml/transformmatrix.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "scene/level_of_detail.h"
#include "scene/polygon_mesh.h"
#include "scene/scene_input.h"
#include "skyview/core/error.h"

namespace skyview {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// libcitygml's messages, kept for our one-line errors and warnings instead of its own printing.
class KeptMessages final : public citygml::CityGMLLogger {
 public:
  KeptMessages() : CityGMLLogger(LOGLEVEL::LL_WARNING) {}
  void log(LOGLEVEL level, const std::string& message, const char*, int) const override {
    std::string& first = level == LOGLEVEL::LL_ERROR ? first_error : first_warning;
    int& count = level == LOGLEVEL::LL_ERROR ? errors : warnings;
    if (first.empty()) first = message.substr(0, 200);
    ++count;
  }
  mutable std::string first_error, first_warning;
  mutable int errors = 0, warnings = 0;
};

// A point of a placed implicit geometry: the template's point through its matrix, then moved to
// the reference point.
struct Placement {
  const double* matrix = nullptr;  // row-major 4 x 4, null: none
  TVec3d reference;
  Vec3d operator()(const TVec3d& p) const {
    if (!matrix) return {p.x, p.y, p.z};
    const double* m = matrix;
    return {m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3] + reference.x,
            m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7] + reference.y,
            m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11] + reference.z};
  }
};

// Calls f(geometry, placement) for every geometry of `object` and its children, nested geometries included.
template <typename F>
void each_geometry(const citygml::CityObject& object, F&& f, int depth = 0) {
  if (depth > 64) return;  // deeper than any city model nests: a malicious file
  std::function<void(const citygml::Geometry&, const Placement&, int)> walk = [&](const citygml::Geometry& g,
                                                                                  const Placement& p, int d) {
    if (d > 64) return;
    f(g, p);
    for (unsigned i = 0; i < g.getGeometriesCount(); ++i) walk(g.getGeometry(i), p, d + 1);
  };
  for (unsigned i = 0; i < object.getGeometriesCount(); ++i) walk(object.getGeometry(i), Placement{}, 0);
  for (unsigned i = 0; i < object.getImplicitGeometryCount(); ++i) {
    const citygml::ImplicitGeometry& ig = object.getImplicitGeometry(i);
    const Placement p{ig.getTransformMatrix().getMatrix(), ig.getReferencePoint()};
    for (unsigned k = 0; k < ig.getGeometriesCount(); ++k) walk(ig.getGeometry(k), p, 0);
  }
  for (unsigned i = 0; i < object.getChildCityObjectsCount(); ++i) {
    each_geometry(object.getChildCityObject(i), f, depth + 1);
  }
}

class CityGmlInput : public SceneInput {
 public:
  // `stream` holds the document; `head` its first bytes (for the version); `name` names it.
  CityGmlInput(std::istream& stream, const std::string& head, const std::string& name, const SceneLoadOptions& o)
      : name_(name) {
    lod_limit_ = lod_limit(o.lod);
    for (const char* v : {"1.0", "2.0", "3.0"}) {
      if (head.find(std::string("opengis.net/citygml/") + v) != std::string::npos) version_ = v;
    }
    if (version_ == "3.0") {
      throw Error("'" + name + "' is CityGML 3.0; libcitygml reads 1.0 and 2.0 (citygml-tools converts 3.0 to 2.0)");
    }
    citygml::ParserParams params;
    params.tesselate = false;    // triangulated here, with shared corners
    params.keepVertices = true;  // the rings' points, which tesselation would otherwise consume
    params.optimize = false;
    params.pruneEmptyObjects = false;
    logger_ = std::make_shared<KeptMessages>();
    try {
      model_ = citygml::load(stream, params, logger_);
    } catch (const std::exception& e) {
      throw Error("cannot read '" + name + "' as CityGML: " + std::string(e.what()).substr(0, 200));
    } catch (...) {  // Xerces' own exceptions, which libcitygml lets through
      throw Error("cannot read '" + name + "' as CityGML: not well-formed XML" +
                  (logger_->first_error.empty() ? std::string() : " (" + logger_->first_error + ")"));
    }
    if (!model_) {
      throw Error("cannot read '" + name + "' as CityGML" +
                  (logger_->first_error.empty() ? std::string() : ": " + logger_->first_error));
    }
    // The CRS: the model's envelope's, else the first geometry's that states one.
    crs_ = model_->getEnvelope().srsName();
    std::array<Vec3d, 2> box{Vec3d{kInf, kInf, kInf}, Vec3d{-kInf, -kInf, -kInf}};
    for (const citygml::CityObject* root : model_->getRootCityObjects()) {
      each_geometry(*root, [&](const citygml::Geometry& g, const Placement& p) {
        if (crs_.empty()) crs_ = g.getSRSName();
        for (unsigned i = 0; i < g.getPolygonsCount(); ++i) {
          const auto polygon = g.getPolygon(i);
          if (!polygon || !polygon->exteriorRing()) continue;
          for (const TVec3d& v : polygon->exteriorRing()->getVertices()) {
            const Vec3d q = p(v);
            if (!std::isfinite(q[0]) || !std::isfinite(q[1]) || !std::isfinite(q[2])) continue;
            for (int k = 0; k < 3; ++k) box[0][k] = std::min(box[0][k], q[k]), box[1][k] = std::max(box[1][k], q[k]);
          }
        }
      });
    }
    if (box[0][0] <= box[1][0]) extent_ = box;
  }

  std::string format() const override { return version_.empty() ? "CityGML" : "CityGML " + version_; }
  std::string declared_crs() const override { return crs_; }
  std::optional<std::array<Vec3d, 2>> extent() const override { return extent_; }

  void add_to(SceneAssembly& scene) override {
    PolygonTriangulator triangulator;
    for (const citygml::CityObject* root : model_->getRootCityObjects()) add_object(scene, triangulator, *root);
    if (logger_->errors > 0) {
      scene.warn("'" + name_ + "': libcitygml reported " + std::to_string(logger_->errors) +
                 " errors (first: " + logger_->first_error + ")");
    }
  }

 private:
  void add_object(SceneAssembly& scene, PolygonTriangulator& triangulator, const citygml::CityObject& object) {
    const std::string name = object.getTypeAsString() + " " + object.getId();
    // The level of detail: the highest not above the limit, over the object and its children.
    double chosen = -kInf;
    bool any = false;
    each_geometry(object, [&](const citygml::Geometry& g, const Placement&) {
      if (g.getPolygonsCount() == 0) return;
      any = true;
      const double lod = g.getLOD();
      if (lod <= lod_limit_) chosen = std::max(chosen, lod);
    });
    if (!any) {
      scene.skip(name, "without polygons");
      return;
    }
    if (chosen == -kInf) {
      scene.skip(name, "without geometry at or below LoD " + lod_text(lod_limit_));
      return;
    }
    PolygonMesh mesh(name);
    std::int64_t flat = 0;
    std::vector<std::vector<Vec3d>> rings;
    each_geometry(object, [&](const citygml::Geometry& g, const Placement& p) {
      if (static_cast<double>(g.getLOD()) != chosen) return;
      for (unsigned i = 0; i < g.getPolygonsCount(); ++i) {
        const auto polygon = g.getPolygon(i);
        if (!polygon || !polygon->exteriorRing()) continue;
        rings.clear();
        rings.emplace_back();
        for (const TVec3d& v : polygon->exteriorRing()->getVertices()) rings.back().push_back(p(v));
        for (const auto& hole : polygon->interiorRings()) {
          if (!hole) continue;
          rings.emplace_back();
          for (const TVec3d& v : hole->getVertices()) rings.back().push_back(p(v));
        }
        if (!mesh.add_polygon(triangulator, rings, polygon->negNormal())) ++flat;
      }
    });
    if (flat > 0) scene.drop_surfaces(flat, "no area", name);
    if (mesh.empty()) {
      scene.skip(name, "no polygon with area");
      return;
    }
    scene.add(mesh.take());
  }

  std::string name_, version_, crs_;
  std::shared_ptr<KeptMessages> logger_;
  std::shared_ptr<const citygml::CityModel> model_;
  double lod_limit_ = kInf;
  std::optional<std::array<Vec3d, 2>> extent_;
};

}  // namespace

std::unique_ptr<SceneInput> open_citygml_text(const std::string& text, const std::string& name,
                                              const SceneLoadOptions& options) {
  std::istringstream stream(text);
  return std::make_unique<CityGmlInput>(stream, text.substr(0, 1 << 16), name, options);
}

std::unique_ptr<SceneInput> open_citygml(const std::string& path, const std::string& head,
                                         const SceneLoadOptions& options) {
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw Error("cannot open '" + path + "'");
  return std::make_unique<CityGmlInput>(stream, head, path, options);
}

}  // namespace skyview
