// Mesh files (OBJ, PLY, glTF/GLB, STL, COLLADA, FBX and the rest Assimp reads): one scene mesh per
// mesh of each node, placed by the node's transforms (in double), polygons triangulated by Assimp,
// corners welded by position. A mesh file has no CRS (SceneLoadOptions::s_srs gives it); Y-up
// formats are turned to z up: (x, y, z) -> (x, -z, y), the file's -z becoming north.
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>

#include "scene/polygon_mesh.h"
#include "scene/scene_input.h"
#include "skyview/core/error.h"
#include "skyview/core/lowercase.h"
#include "skyview/core/number_text.h"

namespace skyview {
namespace {

using Matrix = std::array<double, 16>;  // row-major, as aiMatrix4x4

Matrix to_double(const aiMatrix4x4& m) {
  return {m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4};
}

Matrix multiply(const Matrix& a, const Matrix& b) {
  Matrix c{};
  for (int r = 0; r < 4; ++r) {
    for (int k = 0; k < 4; ++k) {
      for (int j = 0; j < 4; ++j) c[4 * r + j] += a[4 * r + k] * b[4 * k + j];
    }
  }
  return c;
}

constexpr Matrix kIdentity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

// Whether the format's files are y-up as Assimp hands them over: glTF by its specification,
// COLLADA and FBX because Assimp turns them so.
bool y_up_by_format(const std::string& extension) {
  return extension == ".gltf" || extension == ".glb" || extension == ".dae" || extension == ".fbx";
}

class MeshFileInput : public SceneInput {
 public:
  // From a file, or from `bytes` in memory with `hint` its extension (the fuzz target's way in).
  MeshFileInput(const std::string& path, const SceneLoadOptions& o, const std::string* bytes = nullptr,
                const std::string& hint = "")
      : path_(path), extension_(bytes ? "." + hint : lowercase_extension(path)) {
    if (!o.up_axis.empty() && o.up_axis != "y" && o.up_axis != "z") {
      throw Error("the up axis of mesh files is y or z, not '" + o.up_axis + "'");
    }
    y_up_ = o.up_axis.empty() ? y_up_by_format(extension_) : o.up_axis == "y";
    Assimp::Importer importer;
    importer.SetPropertyBool(AI_CONFIG_FBX_CONVERT_TO_M, true);  // FBX states its unit; centimetres are common
    // Triangles only, equal vertices joined (shared corners make closed meshes closed), and the
    // structure checked (indices in range) before anything here reads it.
    const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_ValidateDataStructure;
    const aiScene* scene = bytes ? importer.ReadFileFromMemory(bytes->data(), bytes->size(), flags, hint.c_str())
                                 : importer.ReadFile(path, flags);
    if (!scene) {
      std::string why = importer.GetErrorString();
      std::replace(why.begin(), why.end(), '\n', ' ');
      throw Error("cannot read '" + path + "' as a mesh: " + why.substr(0, 200));
    }
    if (scene->mRootNode) place(*scene, *scene->mRootNode, kIdentity, 0);
    for (const SourceMesh& m : meshes_) {
      for (const Vec3d& p : m.vertices) {
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
        if (!extent_) extent_ = std::array<Vec3d, 2>{p, p};
        for (int k = 0; k < 3; ++k) {
          (*extent_)[0][k] = std::min((*extent_)[0][k], p[k]);
          (*extent_)[1][k] = std::max((*extent_)[1][k], p[k]);
        }
      }
    }
  }

  std::string format() const override {
    std::string e = extension_.size() > 1 ? extension_.substr(1) : "?";
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    return "mesh (" + e + (y_up_ ? ", y up" : ", z up") + ")";
  }
  std::string declared_crs() const override { return ""; }
  std::optional<std::array<Vec3d, 2>> extent() const override { return extent_; }

  void add_to(SceneAssembly& scene) override {
    const std::string file = "'" + path_ + "': ";
    // Assimp holds coordinates in float: far from the file's origin they come in steps.
    double far = 0;
    if (extent_) {
      for (int k = 0; k < 3; ++k) far = std::max({far, std::abs((*extent_)[0][k]), std::abs((*extent_)[1][k])});
    }
    if (far > 1e5) {
      scene.warn(file + "coordinates reach " + number_text(std::round(far)) +
                 " from the file's origin, and Assimp reads them in single precision: steps of " +
                 number_text(std::ldexp(1.0, std::ilogb(far) - 23)) + " there");
    }
    for (const std::string& name : points_or_lines_) scene.skip(name, "points or lines only");
    if (out_of_range_ > 0) scene.drop_triangles(out_of_range_, "indices out of range", "");
    for (SourceMesh& m : meshes_) scene.add(std::move(m));
    meshes_.clear();
  }

 private:
  // Every mesh of `node` and its children, through the transforms down to it.
  void place(const aiScene& scene, const aiNode& node, const Matrix& parent, int depth) {
    if (depth > 256) return;  // deeper than any model nests: a malformed file
    const Matrix m = multiply(parent, to_double(node.mTransformation));
    const std::string file = std::filesystem::path(path_).filename().string();
    for (unsigned k = 0; k < node.mNumMeshes; ++k) {
      const unsigned index = node.mMeshes[k];
      if (index >= scene.mNumMeshes || !scene.mMeshes[index]) continue;
      const aiMesh& mesh = *scene.mMeshes[index];
      const std::string label = mesh.mName.length > 0 ? mesh.mName.C_Str() : "mesh " + std::to_string(index);
      const int use = ++uses_[index];
      const std::string name = file + ":" + label + (use > 1 ? " #" + std::to_string(use) : "");
      std::vector<Vec3d> placed(mesh.mNumVertices);
      for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
        const aiVector3D& v = mesh.mVertices[i];
        const double p[3] = {m[0] * v.x + m[1] * v.y + m[2] * v.z + m[3], m[4] * v.x + m[5] * v.y + m[6] * v.z + m[7],
                             m[8] * v.x + m[9] * v.y + m[10] * v.z + m[11]};
        placed[i] = y_up_ ? Vec3d{p[0], -p[2], p[1]} : Vec3d{p[0], p[1], p[2]};
      }
      // Corners welded by position: a file's vertices differ by normal or texture coordinate too,
      // and a closed surface should be closed here whatever it is textured with.
      PolygonMesh out(name);
      bool faces = false;
      for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        if (face.mNumIndices != 3) continue;  // points and lines
        faces = true;
        if (face.mIndices[0] >= mesh.mNumVertices || face.mIndices[1] >= mesh.mNumVertices ||
            face.mIndices[2] >= mesh.mNumVertices) {
          ++out_of_range_;  // (Assimp's validation should have refused the file)
          continue;
        }
        out.add_triangle(placed[face.mIndices[0]], placed[face.mIndices[1]], placed[face.mIndices[2]]);
      }
      if (!faces && mesh.mNumFaces > 0) {
        points_or_lines_.push_back(name);
        continue;
      }
      meshes_.push_back(out.take());
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c) {
      if (node.mChildren[c]) place(scene, *node.mChildren[c], m, depth + 1);
    }
  }

  std::string path_, extension_;
  bool y_up_ = false;
  std::vector<SourceMesh> meshes_;
  std::vector<std::string> points_or_lines_;
  std::map<unsigned, int> uses_;
  std::int64_t out_of_range_ = 0;
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
                                            const std::string& name, const SceneLoadOptions& options) {
  return std::make_unique<MeshFileInput>(name, options, &bytes, extension);
}

}  // namespace skyview
