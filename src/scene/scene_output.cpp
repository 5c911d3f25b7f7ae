#include "skyview/scene/scene_output.h"

#include <cstdio>
#include <cstring>

#include "scene/scene_crs.h"
#include "skyview/core/error.h"
#include "skyview/raster/raster_io.h"

namespace skyview {
namespace {

template <typename T>
void put(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));  // x86-64 and arm64 are little-endian, as the header says
  out.append(bytes, sizeof(T));
}

}  // namespace

nlohmann::json scene_summary(const Scene& scene) {
  using nlohmann::json;
  const auto b = scene.bounds();
  json bounds = nullptr;
  if (b[0][0] <= b[1][0]) {
    bounds = {{"min", {b[0][0] + scene.origin[0], b[0][1] + scene.origin[1], b[0][2] + scene.origin[2]}},
              {"max", {b[1][0] + scene.origin[0], b[1][1] + scene.origin[1], b[1][2] + scene.origin[2]}}};
  }
  json inputs = json::array();
  for (const SceneInputReport& i : scene.report.inputs) {
    inputs.push_back({{"path", i.path},
                      {"format", i.format},
                      {"crs", i.crs},
                      {"meshes", i.meshes},
                      {"triangles", i.triangles},
                      {"meshes_skipped", i.meshes_skipped},
                      {"surfaces_skipped", i.surfaces_skipped},
                      {"triangles_skipped", i.triangles_skipped}});
  }
  return {{"meshes", scene.meshes.size()},
          {"triangles", scene.triangle_count()},
          {"crs", crs_display_name(scene.crs_wkt)},
          {"crs_wkt", scene.crs_wkt},
          {"origin", {scene.origin[0], scene.origin[1], scene.origin[2]}},
          {"bounds", bounds},
          {"skipped",
           {{"meshes", scene.report.meshes_skipped},
            {"surfaces", scene.report.surfaces_skipped},
            {"triangles", scene.report.triangles_skipped}}},
          {"inputs", inputs},
          {"warnings", scene.report.warnings}};
}

void write_scene_ply(const Scene& scene, const std::string& path, bool overwrite) {
  check_output_writable(path, overwrite);
  std::size_t vertices = 0;
  for (const SceneMesh& m : scene.meshes) vertices += m.vertices.size();
  if (vertices > 0xFFFFFFFFull) throw Error("the scene has too many vertices for a PLY file's 32-bit indices");
  const std::size_t triangles = scene.triangle_count();
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment skyview scene\n";
  out += "comment crs " + crs_display_name(scene.crs_wkt) + "\n";
  char origin[160];
  std::snprintf(origin, sizeof origin, "comment origin %.3f %.3f %.3f (add it to the vertices for CRS coordinates)\n",
                scene.origin[0], scene.origin[1], scene.origin[2]);
  out += origin;
  out += "element vertex " + std::to_string(vertices) + "\nproperty float x\nproperty float y\nproperty float z\n";
  out += "element face " + std::to_string(triangles) + "\nproperty list uchar uint vertex_indices\nend_header\n";
  out.reserve(out.size() + vertices * 12 + triangles * 13);
  for (const SceneMesh& m : scene.meshes) {
    for (const Vec3f& v : m.vertices) put(out, v[0]), put(out, v[1]), put(out, v[2]);
  }
  std::uint32_t first = 0;
  for (const SceneMesh& m : scene.meshes) {
    for (const auto& t : m.triangles) {
      put(out, std::uint8_t{3});
      put(out, first + t[0]), put(out, first + t[1]), put(out, first + t[2]);
    }
    first += static_cast<std::uint32_t>(m.vertices.size());
  }
  write_output_file(path, out, overwrite);
}

}  // namespace skyview
