#pragma once
// Scenes the render tests look at: boxes with outward-turned triangles, a ground plane, and an OBJ
// writer so the command line sees the same scene.
#include <array>
#include <cstdio>
#include <string>

#include "skyview/scene/scene.h"

namespace skyview::test {

// A closed box [lo, hi], triangles counter-clockwise seen from outside.
inline SceneMesh box_mesh(const std::string& name, Vec3f lo, Vec3f hi) {
  SceneMesh m;
  m.name = name;
  for (int k = 0; k < 8; ++k)
    m.vertices.push_back({k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]});
  const std::array<std::array<std::uint32_t, 4>, 6> quads{{
      {0, 2, 3, 1},  // bottom (z lo), seen from below
      {4, 5, 7, 6},  // top
      {0, 1, 5, 4},  // y lo
      {2, 6, 7, 3},  // y hi
      {0, 4, 6, 2},  // x lo
      {1, 3, 7, 5},  // x hi
  }};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

// A square ground plane at z = 0, facing up, `half` metres each side of the origin.
inline SceneMesh ground_mesh(float half) {
  SceneMesh m;
  m.name = "ground";
  m.vertices = {{-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

// A canyon along y: two walls `height` high, `width` apart (floor centre line at x = 0), `length`
// long, on a ground plane; the walls are 30 m thick blocks.
inline Scene canyon_scene(float width, float height, float length) {
  Scene s;
  s.meshes.push_back(ground_mesh(length / 2 + 50));
  s.meshes.push_back(box_mesh("west", {-width / 2 - 30, -length / 2, 0}, {-width / 2, length / 2, height}));
  s.meshes.push_back(box_mesh("east", {width / 2, -length / 2, 0}, {width / 2 + 30, length / 2, height}));
  return s;
}

// A porch: a slab 6 x 6 m, 0.3 m thick, its underside 3 m up, on four 0.2 m posts at its corners.
inline Scene porch_scene() {
  Scene s;
  s.meshes.push_back(ground_mesh(200));
  s.meshes.push_back(box_mesh("slab", {-3, -3, 3}, {3, 3, 3.3f}));
  for (float x : {-3.0f, 2.8f}) {
    for (float y : {-3.0f, 2.8f}) s.meshes.push_back(box_mesh("post", {x, y, 0}, {x + 0.2f, y + 0.2f, 3}));
  }
  return s;
}

inline void write_obj(const Scene& s, const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  std::size_t base = 1;
  for (const SceneMesh& m : s.meshes) {
    std::fprintf(f, "o %s\n", m.name.c_str());
    for (const Vec3f& v : m.vertices) std::fprintf(f, "v %g %g %g\n", v[0], v[1], v[2]);
    for (const auto& t : m.triangles) {
      std::fprintf(f, "f %zu %zu %zu\n", base + t[0], base + t[1], base + t[2]);
    }
    base += m.vertices.size();
  }
  std::fclose(f);
}

}  // namespace skyview::test
