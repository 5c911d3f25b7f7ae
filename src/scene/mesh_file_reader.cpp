// Mesh files (OBJ, PLY, glTF/GLB, STL, COLLADA, FBX and the rest Assimp reads): one scene mesh per
// mesh of each node, placed by the nodes' transforms. Assimp runs in a child process (Assimp 5.2
// crashes, aborts or loops for ever on some malformed files); here every face it sent is checked,
// polygons are triangulated as every reader's are (PolygonTriangulator) and corners welded by
// position. A mesh file has no CRS (SceneLoadOptions::s_srs gives it); y-up formats are turned to
// z up: (x, y, z) -> (x, -z, y), the file's -z becoming north.
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "scene/assimp_import.h"
#include "scene/isolated_call.h"
#include "scene/polygon_mesh.h"
#include "scene/scene_input.h"
#include "skyview/core/error.h"
#include "skyview/core/lowercase.h"
#include "skyview/core/number_text.h"

namespace skyview {
namespace {

// Whether the format's files are y-up as Assimp hands them over: glTF by its specification,
// COLLADA and FBX because Assimp turns them so.
bool y_up_by_format(const std::string& extension) {
  return extension == ".gltf" || extension == ".glb" || extension == ".dae" || extension == ".fbx";
}

// Assimp 5.2's PLY parser loops for ever on a header without its end_header line (a truncated
// file; found by fuzz_mesh_reader): refused at once rather than after the child's time runs out.
void check_ply_header(const std::string& start, const std::string& path) {
  if (start.rfind("ply", 0) != 0 || start.find("\nend_header") == std::string::npos) {
    throw Error("'" + path +
                "' is not a complete PLY file: its header does not start with 'ply' and end with 'end_header' in "
                "its first megabyte");
  }
}

class MeshFileInput : public SceneInput {
 public:
  // From a file, or from `bytes` in memory with `hint` its extension (the fuzz target's way in).
  MeshFileInput(const std::string& path, const SceneLoadOptions& o, const std::string* bytes = nullptr,
                const std::string& hint = "", double timeout_seconds = 0.0)
      : path_(path), extension_(bytes ? "." + hint : lowercase_extension(path)) {
    if (!o.up_axis.empty() && o.up_axis != "y" && o.up_axis != "z") {
      throw Error("the up axis of mesh files is y or z, not '" + o.up_axis + "'");
    }
    y_up_ = o.up_axis.empty() ? y_up_by_format(extension_) : o.up_axis == "y";
    if (extension_ == ".ply") check_ply_header(bytes ? bytes->substr(0, 1 << 20) : file_start(path, 1 << 20), path);
    // The child's time: a minute and 4 s a megabyte (Assimp parses tens of megabytes a second).
    std::error_code ec;
    const double megabytes = (bytes ? bytes->size() : static_cast<double>(std::filesystem::file_size(path, ec))) / 1e6;
    const double default_timeout = 60.0 + 4.0 * (ec ? 0.0 : megabytes);
    const std::string label = std::filesystem::path(path).filename().string();
    const IsolatedResult r = run_isolated([&] { return import_with_assimp(path, bytes, hint, label, y_up_); },
                                          timeout_seconds > 0 ? timeout_seconds : default_timeout);
    if (!r.ok) throw Error("cannot read '" + path + "' as a mesh: Assimp " + r.failure + " on it");
    RawMeshes raw = decode_raw_meshes(r.bytes);
    if (!raw.failure.empty()) throw Error("cannot read '" + path + "' as a mesh: " + raw.failure);
    for (RawMesh& m : raw.meshes) build(m);
  }

  std::string format() const override {
    std::string e = extension_.size() > 1 ? extension_.substr(1) : "?";
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    return "mesh (" + e + (y_up_ ? ", y up" : ", z up") + ")";
  }
  std::string declared_crs() const override { return ""; }
  std::optional<std::array<Vec3d, 2>> extent() const override { return extent_; }

  void add_to(SceneAssembly& scene) override {
    // Assimp holds coordinates in float: far from the file's origin they come in steps.
    double far = 0;
    if (extent_) {
      for (int k = 0; k < 3; ++k) far = std::max({far, std::abs((*extent_)[0][k]), std::abs((*extent_)[1][k])});
    }
    if (far > 1e5) {
      scene.warn("'" + path_ + "': coordinates reach " + number_text(std::round(far)) +
                 " from the file's origin, and Assimp reads them in single precision: steps of " +
                 number_text(std::ldexp(1.0, std::ilogb(far) - 23)) + " there");
    }
    for (const std::string& name : points_or_lines_) scene.skip(name, "points or lines only");
    for (const auto& [name, count] : out_of_range_) scene.drop_surfaces(count, "indices out of range", name);
    for (const auto& [name, count] : flat_) scene.drop_surfaces(count, "polygons without area", name);
    for (SourceMesh& m : meshes_) scene.add(std::move(m));
    meshes_.clear();
  }

 private:
  // One mesh from the child's faces, each checked against the vertices there are.
  void build(RawMesh& raw) {
    PolygonMesh mesh(raw.name);
    std::vector<std::vector<Vec3d>> ring(1);
    std::int64_t polygons = 0, out_of_range = 0, flat = 0;
    for (std::size_t i = 0; i < raw.faces.size();) {
      const std::uint32_t n = raw.faces[i++];
      if (n > raw.faces.size() - i) {  // the list ends inside a face: the child's bytes are broken
        ++out_of_range;
        break;
      }
      const std::uint32_t* corner = raw.faces.data() + i;
      i += n;
      if (n < 3) continue;  // points and lines
      ++polygons;
      ring[0].clear();
      for (std::uint32_t k = 0; k < n && corner[k] < raw.vertices.size(); ++k) {
        ring[0].push_back(raw.vertices[corner[k]]);
      }
      if (ring[0].size() != n) {
        ++out_of_range;
      } else if (n == 3) {
        mesh.add_triangle(ring[0][0], ring[0][1], ring[0][2]);
      } else if (!mesh.add_polygon(triangulator_, ring)) {
        ++flat;
      }
    }
    if (polygons == 0 && !raw.faces.empty()) {
      points_or_lines_.push_back(raw.name);
      return;
    }
    if (out_of_range > 0) out_of_range_.emplace_back(raw.name, out_of_range);
    if (flat > 0) flat_.emplace_back(raw.name, flat);
    SourceMesh m = mesh.take();
    for (const Vec3d& p : m.vertices) {
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
      if (!extent_) extent_ = std::array<Vec3d, 2>{p, p};
      for (int k = 0; k < 3; ++k) {
        (*extent_)[0][k] = std::min((*extent_)[0][k], p[k]);
        (*extent_)[1][k] = std::max((*extent_)[1][k], p[k]);
      }
    }
    meshes_.push_back(std::move(m));
  }

  std::string path_, extension_;
  bool y_up_ = false;
  PolygonTriangulator triangulator_;
  std::vector<SourceMesh> meshes_;
  std::vector<std::string> points_or_lines_;
  std::vector<std::pair<std::string, std::int64_t>> out_of_range_, flat_;  // per mesh
  std::optional<std::array<Vec3d, 2>> extent_;
};

}  // namespace

bool mesh_format_known(const std::string& path) {
  const std::string ext = lowercase_extension(path);
  return !ext.empty() && Assimp::Importer().IsExtensionSupported(ext);
}

std::unique_ptr<SceneInput> open_mesh_file(const std::string& path, const SceneLoadOptions& options) {
  return std::make_unique<MeshFileInput>(path, options);
}

std::unique_ptr<SceneInput> open_mesh_bytes(const std::string& bytes, const std::string& extension,
                                            const std::string& name, const SceneLoadOptions& options,
                                            double timeout_seconds) {
  return std::make_unique<MeshFileInput>(name, options, &bytes, extension, timeout_seconds);
}

}  // namespace skyview
