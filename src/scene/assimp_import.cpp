#include "scene/assimp_import.h"

#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <array>
#include <cstring>
#include <map>

#include "skyview/core/error.h"

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

template <typename T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

void put_text(std::string& out, const std::string& s) {
  put(out, static_cast<std::uint64_t>(s.size()));
  out += s;
}

// Every mesh of `node` and its children, through the transforms down to it, encoded into `out`.
struct Placer {
  const aiScene& scene;
  std::string label;
  bool y_up;
  std::map<unsigned, int> uses;
  std::uint64_t count = 0;
  std::string out;

  void place(const aiNode& node, const Matrix& parent, int depth) {
    if (depth > 256) return;  // deeper than any model nests: a malformed file
    const Matrix m = multiply(parent, to_double(node.mTransformation));
    for (unsigned k = 0; k < node.mNumMeshes; ++k) {
      const unsigned index = node.mMeshes[k];
      if (index >= scene.mNumMeshes || !scene.mMeshes[index]) continue;
      const aiMesh& mesh = *scene.mMeshes[index];
      const std::string name = mesh.mName.length > 0 ? mesh.mName.C_Str() : "mesh " + std::to_string(index);
      const int use = ++uses[index];
      put_text(out, label + ":" + name + (use > 1 ? " #" + std::to_string(use) : ""));
      put(out, static_cast<std::uint64_t>(mesh.mNumVertices));
      for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
        const aiVector3D& v = mesh.mVertices[i];
        const double p[3] = {m[0] * v.x + m[1] * v.y + m[2] * v.z + m[3], m[4] * v.x + m[5] * v.y + m[6] * v.z + m[7],
                             m[8] * v.x + m[9] * v.y + m[10] * v.z + m[11]};
        put(out, y_up ? Vec3d{p[0], -p[2], p[1]} : Vec3d{p[0], p[1], p[2]});
      }
      std::uint64_t words = 0;
      for (unsigned f = 0; f < mesh.mNumFaces; ++f)
        words += 1 + (mesh.mFaces[f].mIndices ? mesh.mFaces[f].mNumIndices : 0);
      put(out, words);
      for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        const std::uint32_t n = face.mIndices ? face.mNumIndices : 0;
        put(out, n);
        out.append(reinterpret_cast<const char*>(face.mIndices), n * sizeof(std::uint32_t));
      }
      ++count;
    }
    for (unsigned c = 0; c < node.mNumChildren; ++c) {
      if (node.mChildren[c]) place(*node.mChildren[c], m, depth + 1);
    }
  }
};

std::string failure(const std::string& why) {
  std::string out;
  put(out, std::uint8_t{0});
  put_text(out, why);
  return out;
}

// Reads back what put wrote, trusting no length beyond the bytes there are.
class Reader {
 public:
  explicit Reader(const std::string& s) : s_(s) {}
  template <typename T>
  T get() {
    T v{};
    need(sizeof v);
    std::memcpy(&v, s_.data() + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  std::string text() {
    const std::uint64_t n = get<std::uint64_t>();
    need(n);
    std::string t = s_.substr(at_, n);
    at_ += n;
    return t;
  }
  template <typename T>
  void items(std::vector<T>& v) {  // a count, then that many items
    const std::uint64_t n = get<std::uint64_t>();
    if (n > (s_.size() - at_) / sizeof(T)) need(s_.size() + 1);
    v.resize(n);
    std::memcpy(v.data(), s_.data() + at_, n * sizeof(T));
    at_ += n * sizeof(T);
  }

 private:
  void need(std::uint64_t n) const {
    if (n > s_.size() - at_) throw Error("the mesh reader's process sent a short result");
  }
  const std::string& s_;
  std::size_t at_ = 0;
};

}  // namespace

std::string import_with_assimp(const std::string& path, const std::string* bytes, const std::string& hint,
                               const std::string& label, bool y_up) {
  try {
    Assimp::Importer importer;
    importer.SetPropertyBool(AI_CONFIG_FBX_CONVERT_TO_M, true);  // FBX states its unit; centimetres are common
    // The structure checked (indices in range) and nothing more: polygons are triangulated by the
    // parent, as every reader's are (Assimp 5.2's triangulation aborts on some malformed faces).
    const unsigned flags = aiProcess_ValidateDataStructure;
    const aiScene* scene = bytes ? importer.ReadFileFromMemory(bytes->data(), bytes->size(), flags, hint.c_str())
                                 : importer.ReadFile(path, flags);
    if (!scene) {
      std::string why = importer.GetErrorString();
      std::replace(why.begin(), why.end(), '\n', ' ');
      return failure(why.substr(0, 200));
    }
    Placer placer{*scene, label, y_up, {}, 0, {}};
    if (scene->mRootNode) placer.place(*scene->mRootNode, kIdentity, 0);
    std::string out;
    put(out, std::uint8_t{1});
    put(out, placer.count);
    return out + placer.out;
  } catch (const std::exception& e) {
    return failure(e.what());
  }
}

RawMeshes decode_raw_meshes(const std::string& bytes) {
  Reader in(bytes);
  RawMeshes r;
  if (in.get<std::uint8_t>() == 0) {
    r.failure = in.text();
    return r;
  }
  for (std::uint64_t n = in.get<std::uint64_t>(); n > 0; --n) {
    RawMesh m;
    m.name = in.text();
    in.items(m.vertices);
    in.items(m.faces);
    r.meshes.push_back(std::move(m));
  }
  return r;
}

}  // namespace skyview
