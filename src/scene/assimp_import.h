#pragma once
// What Assimp makes of a mesh file, as plain data that crosses a pipe: the meshes of every node,
// placed by the nodes' transforms (in double) and turned z up where the file is y up, their faces
// as given (any number of corners). Made in a child process (isolated_call.h), read in the parent,
// which checks every index before it uses it.
#include <cstdint>
#include <string>
#include <vector>

#include "skyview/scene/scene.h"

namespace skyview {

struct RawMesh {
  std::string name;  // "model.obj:mesh 3", "model.gltf:Roof #2" for its second use
  std::vector<Vec3d> vertices;
  std::vector<std::uint32_t> faces;  // per face: its corner count n, then n vertex indices
};

struct RawMeshes {
  std::string failure;  // Assimp's reason where it read nothing
  std::vector<RawMesh> meshes;
};

// Imports `path` (or `bytes`, with `hint` its extension) and returns the meshes encoded; runs in
// the child, never throws. `label` names the meshes ("model.obj").
std::string import_with_assimp(const std::string& path, const std::string* bytes, const std::string& hint,
                               const std::string& label, bool y_up);

// The parent's side: decodes what import_with_assimp sent. Throws skyview::Error for bytes that do
// not hold what it writes.
RawMeshes decode_raw_meshes(const std::string& bytes);

}  // namespace skyview
