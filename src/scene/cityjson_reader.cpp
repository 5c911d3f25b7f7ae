// CityJSON 1.0, 1.1 and 2.0 (and CityJSONSeq, one CityJSONFeature a line) read with nlohmann-json:
// no Debian library reads the format. Vertices are integers scaled and translated by "transform"
// (1.1, 2.0; optional in 1.0); each city object becomes one mesh of its geometries at the chosen
// level of detail (MultiSurface, CompositeSurface, Solid, MultiSolid, CompositeSolid, and
// GeometryInstance of "geometry-templates"); semantics, materials and textures are not read.
#include <nlohmann/json.hpp>

#include <algorithm>
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

using nlohmann::json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The member `key` of `j` where `j` is an object that has it, else null.
const json* member(const json& j, const char* key) {
  if (!j.is_object()) return nullptr;
  const auto it = j.find(key);
  return it == j.end() ? nullptr : &*it;
}

bool read_triple(const json* j, std::array<double, 3>& out) {
  if (!j || !j->is_array() || j->size() != 3) return false;
  for (int k = 0; k < 3; ++k) {
    if (!(*j)[k].is_number()) return false;
    out[k] = (*j)[k].get<double>();
  }
  return true;
}

// A geometry's level of detail: a string ("2.2") from 1.1 on, a number in 1.0; NaN when absent.
double lod_of(const json& geometry) {
  const json* lod = member(geometry, "lod");
  if (!lod) return kNaN;
  if (lod->is_number()) return lod->get<double>();
  if (lod->is_string()) {
    try {
      std::size_t used = 0;
      const double v = std::stod(lod->get<std::string>(), &used);
      return used > 0 ? v : kNaN;
    } catch (const std::exception&) {
      return kNaN;
    }
  }
  return kNaN;
}

// How deep a geometry type's surfaces lie in its "boundaries": surfaces, shells of surfaces,
// solids of shells; 0 for types without surfaces (points, lines), -1 for unknown ones.
int surface_depth(const std::string& type) {
  if (type == "MultiSurface" || type == "CompositeSurface") return 1;
  if (type == "Solid") return 2;
  if (type == "MultiSolid" || type == "CompositeSolid") return 3;
  if (type == "MultiPoint" || type == "MultiLineString") return 0;
  return -1;
}

// One city model's vertices and templates, shared by its objects (a CityJSONSeq feature brings
// its own vertices).
struct Vertices {
  std::vector<Vec3d> points;  // NaN where a vertex is not three numbers
  std::int64_t malformed = 0;
};

struct Templates {
  const json* list = nullptr;  // "templates"
  std::vector<Vec3d> points;   // "vertices-templates", real coordinates
};

class CityJsonInput : public SceneInput {
 public:
  CityJsonInput(const std::string& text, const std::string& name, const SceneLoadOptions& options) : name_(name) {
    lod_limit_ = lod_limit(options.lod);
    parse(text);
    decode_header();
    // The extent: the file's own where it states one, else its vertices'.
    std::array<Vec3d, 2> box{Vec3d{kInf, kInf, kInf}, Vec3d{-kInf, -kInf, -kInf}};
    const json* meta = member(header_, "metadata");
    const json* stated = meta ? member(*meta, "geographicalExtent") : nullptr;
    if (stated && stated->is_array() && stated->size() == 6 &&
        std::all_of(stated->begin(), stated->end(), [](const json& v) { return v.is_number(); })) {
      for (int k = 0; k < 3; ++k) box[0][k] = (*stated)[k].get<double>(), box[1][k] = (*stated)[k + 3].get<double>();
    } else {
      for (const Document& d : documents_) {
        for (const Vec3d& p : d.vertices.points) {
          if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
          for (int k = 0; k < 3; ++k) box[0][k] = std::min(box[0][k], p[k]), box[1][k] = std::max(box[1][k], p[k]);
        }
      }
    }
    if (box[0][0] <= box[1][0] && std::isfinite(box[0][0]) && std::isfinite(box[1][0])) extent_ = box;
  }

  std::string format() const override { return (seq_ ? "CityJSONSeq " : "CityJSON ") + version_; }
  std::string declared_crs() const override { return crs_; }
  std::optional<std::array<Vec3d, 2>> extent() const override { return extent_; }

  void add_to(SceneAssembly& scene) override {
    PolygonTriangulator triangulator;
    std::int64_t malformed = 0;
    for (const Document& d : documents_) {
      malformed += d.vertices.malformed;
      const json* objects = member(*d.root, "CityObjects");
      if (!objects || !objects->is_object()) continue;
      for (const auto& [id, object] : objects->items()) add_object(scene, triangulator, id, object, d.vertices);
    }
    if (malformed > 0) {
      scene.warn("'" + name_ + "': " + std::to_string(malformed) +
                 " vertices are not three numbers; the surfaces on them are left out");
    }
  }

 private:
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  struct Document {
    const json* root;
    Vertices vertices;
  };

  void parse(const std::string& text) {
    try {
      header_ = json::parse(text);
      documents_.push_back({&header_, {}});
    } catch (const json::exception& whole) {  // parse_error, or out_of_range for a number past double
      // CityJSONSeq: a CityJSON header on the first line, then one CityJSONFeature a line.
      std::istringstream lines(text);
      std::string line;
      bool first = true;
      try {
        while (std::getline(lines, line)) {
          if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
          json j = json::parse(line);
          if (first) {
            header_ = std::move(j);
            first = false;
          } else {
            const json* type = member(j, "type");
            if (!type || *type != "CityJSONFeature") {
              throw Error("'" + name_ + "' is not CityJSON: a line after the first is not a CityJSONFeature");
            }
            features_.push_back(std::move(j));
          }
        }
      } catch (const json::exception&) {
        throw Error("'" + name_ + "' is not valid JSON: " + std::string(whole.what()).substr(0, 160));
      }
      if (first || features_.empty()) {
        throw Error("'" + name_ + "' is not valid JSON: " + std::string(whole.what()).substr(0, 160));
      }
      seq_ = true;
      documents_.push_back({&header_, {}});
      for (const json& f : features_) documents_.push_back({&f, {}});
    }
  }

  void decode_header() {
    const json* type = member(header_, "type");
    if (!type || *type != "CityJSON")
      throw Error("'" + name_ + "' is JSON but not CityJSON (no \"type\": \"CityJSON\")");
    const json* version = member(header_, "version");
    version_ = version && version->is_string() ? version->get<std::string>() : "";
    if (version_ != "1.0" && version_ != "1.1" && version_ != "2.0") {
      throw Error("'" + name_ + "' is CityJSON version '" + version_ + "'; versions 1.0, 1.1 and 2.0 are read");
    }
    std::array<double, 3> scale{1, 1, 1}, translate{0, 0, 0};
    if (const json* t = member(header_, "transform")) {
      if (!read_triple(member(*t, "scale"), scale) || !read_triple(member(*t, "translate"), translate) ||
          !std::all_of(scale.begin(), scale.end(), [](double s) { return std::isfinite(s) && s != 0; }) ||
          !std::all_of(translate.begin(), translate.end(), [](double s) { return std::isfinite(s); })) {
        throw Error("'" + name_ + "' has a \"transform\" without three finite scales (not zero) and translations");
      }
    } else if (version_ != "1.0") {
      throw Error("'" + name_ + "' is CityJSON " + version_ + " without the \"transform\" that version requires");
    }
    if (const json* meta = member(header_, "metadata")) {
      const json* rs = member(*meta, "referenceSystem");
      if (rs && rs->is_string()) crs_ = rs->get<std::string>();
    }
    for (Document& d : documents_) {
      const json* vertices = member(*d.root, "vertices");
      if (!vertices || !vertices->is_array()) {
        if (d.root == &header_ && !seq_) throw Error("'" + name_ + "' has no \"vertices\" array");
        continue;
      }
      d.vertices.points.reserve(vertices->size());
      for (const json& v : *vertices) {
        std::array<double, 3> p;
        if (!read_triple(&v, p)) {
          d.vertices.points.push_back({kNaN, kNaN, kNaN});
          ++d.vertices.malformed;
          continue;
        }
        d.vertices.points.push_back(
            {p[0] * scale[0] + translate[0], p[1] * scale[1] + translate[1], p[2] * scale[2] + translate[2]});
      }
    }
    if (const json* gt = member(header_, "geometry-templates")) {
      templates_.list = member(*gt, "templates");
      if (const json* tv = member(*gt, "vertices-templates"); tv && tv->is_array()) {
        for (const json& v : *tv) {
          std::array<double, 3> p;
          templates_.points.push_back(read_triple(&v, p) ? Vec3d{p[0], p[1], p[2]} : Vec3d{kNaN, kNaN, kNaN});
        }
      }
      if (templates_.list && !templates_.list->is_array()) templates_.list = nullptr;
    }
  }

  // The geometry a GeometryInstance stands for, or null.
  const json* template_of(const json& instance) const {
    const json* t = member(instance, "template");
    if (!templates_.list || !t || !t->is_number_unsigned()) return nullptr;
    const std::size_t i = t->get<std::size_t>();
    return i < templates_.list->size() ? &(*templates_.list)[i] : nullptr;
  }

  double geometry_lod(const json& g) const {
    const json* type = member(g, "type");
    if (type && *type == "GeometryInstance") {
      const json* t = template_of(g);
      return t ? lod_of(*t) : kNaN;
    }
    return lod_of(g);
  }

  void add_object(SceneAssembly& scene, PolygonTriangulator& triangulator, const std::string& id, const json& object,
                  const Vertices& vertices) {
    const json* type = member(object, "type");
    const std::string name = (type && type->is_string() ? type->get<std::string>() + " " : "") + id;
    const json* geometries = member(object, "geometry");
    if (!geometries || !geometries->is_array() || geometries->empty()) {
      // A parent whose children hold the geometry (a Building of BuildingParts) is no gap.
      const json* children = member(object, "children");
      if (!children || !children->is_array() || children->empty()) scene.skip(name, "without geometry");
      return;
    }
    // The level of detail: the highest not above the limit.
    double chosen = -kInf;
    for (const json& g : *geometries) {
      const double lod = geometry_lod(g);
      if (!std::isnan(lod) && lod <= lod_limit_) chosen = std::max(chosen, lod);
    }
    if (chosen == -kInf) {
      scene.skip(name, std::isinf(lod_limit_) ? "without a level of detail"
                                              : "without geometry at or below LoD " + lod_text(lod_limit_));
      return;
    }
    PolygonMesh mesh(name);
    std::int64_t bad_surfaces = 0, flat_surfaces = 0;
    std::vector<std::string> other_types;
    for (const json& g : *geometries) {
      if (geometry_lod(g) != chosen) continue;
      const json* gtype = member(g, "type");
      const std::string t = gtype && gtype->is_string() ? gtype->get<std::string>() : "";
      if (t == "GeometryInstance") {
        add_instance(triangulator, g, vertices, mesh, bad_surfaces, flat_surfaces, other_types);
        continue;
      }
      const int depth = surface_depth(t);
      if (depth < 0) other_types.push_back(t.empty() ? "untyped" : t);
      if (depth <= 0) continue;
      add_surfaces(triangulator, member(g, "boundaries"), depth, vertices.points, mesh, bad_surfaces, flat_surfaces);
    }
    if (bad_surfaces > 0) scene.drop_surfaces(bad_surfaces, "rings that index no vertex", name);
    if (flat_surfaces > 0) scene.drop_surfaces(flat_surfaces, "no area", name);
    if (mesh.empty()) {
      scene.skip(name, !other_types.empty() ? "geometry type " + other_types.front() : "no surface with area");
      return;
    }
    scene.add(mesh.take());
  }

  // A GeometryInstance: its template's surfaces, each point p placed at M p + the reference point.
  void add_instance(PolygonTriangulator& triangulator, const json& instance, const Vertices& vertices,
                    PolygonMesh& mesh, std::int64_t& bad, std::int64_t& flat, std::vector<std::string>& other) {
    const json* geometry = template_of(instance);
    const json* reference = member(instance, "boundaries");
    const json* matrix = member(instance, "transformationMatrix");
    if (!geometry || !reference || !reference->is_array() || reference->size() != 1 ||
        !(*reference)[0].is_number_unsigned() || (*reference)[0].get<std::size_t>() >= vertices.points.size() ||
        !matrix || !matrix->is_array() || matrix->size() != 16 ||
        !std::all_of(matrix->begin(), matrix->end(), [](const json& v) { return v.is_number(); })) {
      ++bad;
      return;
    }
    const Vec3d anchor = vertices.points[(*reference)[0].get<std::size_t>()];
    double m[16];
    for (int k = 0; k < 16; ++k) m[k] = (*matrix)[k].get<double>();
    std::vector<Vec3d> placed(templates_.points.size());
    for (std::size_t i = 0; i < placed.size(); ++i) {
      const Vec3d& p = templates_.points[i];
      for (int r = 0; r < 3; ++r)
        placed[i][r] = m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3] + anchor[r];
    }
    const json* gtype = member(*geometry, "type");
    const std::string t = gtype && gtype->is_string() ? gtype->get<std::string>() : "";
    const int depth = surface_depth(t);
    if (depth < 0) other.push_back("template " + (t.empty() ? "untyped" : t));
    if (depth <= 0) return;
    add_surfaces(triangulator, member(*geometry, "boundaries"), depth, placed, mesh, bad, flat);
  }

  // Walks `boundaries` down `depth` levels of arrays to its surfaces (arrays of rings of indices).
  void add_surfaces(PolygonTriangulator& triangulator, const json* boundaries, int depth,
                    const std::vector<Vec3d>& points, PolygonMesh& mesh, std::int64_t& bad, std::int64_t& flat) {
    if (!boundaries || !boundaries->is_array()) {
      ++bad;
      return;
    }
    if (depth > 1) {
      for (const json& part : *boundaries) add_surfaces(triangulator, &part, depth - 1, points, mesh, bad, flat);
      return;
    }
    for (const json& surface : *boundaries) {
      rings_.clear();
      bool ok = surface.is_array() && !surface.empty();
      for (const json& ring : ok ? surface : json::array()) {
        if (!ring.is_array()) {
          ok = false;
          break;
        }
        rings_.emplace_back();
        for (const json& index : ring) {
          if (!index.is_number_unsigned() || index.get<std::uint64_t>() >= points.size()) {
            ok = false;
            break;
          }
          rings_.back().push_back(points[index.get<std::size_t>()]);
        }
        if (!ok) break;
      }
      if (!ok) {
        ++bad;
      } else if (!mesh.add_polygon(triangulator, rings_)) {
        ++flat;
      }
    }
  }

  std::string name_;
  json header_;
  std::vector<json> features_;  // CityJSONSeq
  std::vector<Document> documents_;
  Templates templates_;
  bool seq_ = false;
  std::string version_, crs_;
  double lod_limit_ = kInf;
  std::optional<std::array<Vec3d, 2>> extent_;
  std::vector<std::vector<Vec3d>> rings_;  // reused between surfaces
};

}  // namespace

std::unique_ptr<SceneInput> open_cityjson_text(const std::string& text, const std::string& name,
                                               const SceneLoadOptions& options) {
  return std::make_unique<CityJsonInput>(text, name, options);
}

std::unique_ptr<SceneInput> open_cityjson(const std::string& path, const SceneLoadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw Error("cannot read '" + path + "'");
  return open_cityjson_text(text.str(), path, options);
}

}  // namespace skyview
