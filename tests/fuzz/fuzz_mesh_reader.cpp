// libFuzzer target for the mesh-file path (src/scene/mesh_file_reader.cpp over Assimp): the first
// byte picks the format (OBJ, PLY, STL, OFF, glTF, GLB), the rest is the file. Whatever Assimp makes
// of it (NaN vertices, empty meshes, points and lines, deep node trees), our walk must end in a
// skyview::Error or a counted skip (a crash or hang of Assimp itself, in its child process, too). Only skyview::Error
// is caught here: any other exception, crash, sanitizer report, hang or runaway allocation is a finding. Run it with
// scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_scene_support.h"
#include "scene/scene_input.h"
#include "skyview/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* formats[] = {"obj", "ply", "stl", "off", "gltf", "glb"};
  const char* format = formats[data[0] % 6];
  try {
    // Assimp runs in a child process; 5 s for it, within libFuzzer's 10 s.
    const auto input = skyview::open_mesh_bytes(std::string(reinterpret_cast<const char*>(data + 1), size - 1), format,
                                                "fuzz", {}, 5.0);
    skyview::fuzz::add_to_scene(*input);
  } catch (const skyview::Error&) {
    // The documented way to reject a bad file.
  }
  return 0;
}
