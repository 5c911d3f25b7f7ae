#pragma once
// Helpers of the scene tests: the real city models of ../shared/sample_data/city3d (skipped with a
// message where absent), and the measures a mesh is checked by: closedness, area, volume.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <utility>

#include "skyview/scene/scene.h"
#include "temp_dir.h"

namespace skyview::test {

inline std::string city3d_file(const std::string& name) {
  const std::string path = std::string(SKYVIEW_SHARED_DIR) + "/sample_data/city3d/" + name;
  return std::filesystem::exists(path) ? path : std::string();
}

#define REQUIRE_CITY3D(path) \
  if ((path).empty()) GTEST_SKIP() << "../shared/sample_data/city3d is absent: real-data test skipped"

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// Closed and consistently turned: every edge is used exactly once in each direction.
inline bool watertight(const SceneMesh& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    if (count != 1) return false;
    const auto back = directed.find({edge.second, edge.first});
    if (back == directed.end() || back->second != 1) return false;
  }
  return !directed.empty();
}

inline std::array<double, 3> normal_of(const SceneMesh& m, const std::array<std::uint32_t, 3>& t) {
  const Vec3f &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
  const double u[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
  const double v[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
  return {0.5 * (u[1] * v[2] - u[2] * v[1]), 0.5 * (u[2] * v[0] - u[0] * v[2]), 0.5 * (u[0] * v[1] - u[1] * v[0])};
}

inline double surface_area(const SceneMesh& m) {
  double a = 0;
  for (const auto& t : m.triangles) {
    const auto n = normal_of(m, t);
    a += std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }
  return a;
}

// Area of the triangles facing up (normal z > 0), projected on the ground: a flat roof's area.
inline double upward_area(const SceneMesh& m) {
  double a = 0;
  for (const auto& t : m.triangles) a += std::max(0.0, normal_of(m, t)[2]);
  return a;
}

// The enclosed volume by the divergence theorem: the sum over triangles of (a . (b x c)) / 6,
// positive when the triangles turn outward.
inline double enclosed_volume(const SceneMesh& m) {
  double v = 0;
  const Vec3f& o = m.vertices.front();  // near the mesh: smaller rounding than the scene origin
  for (const auto& t : m.triangles) {
    double p[3][3];
    for (int k = 0; k < 3; ++k) {
      for (int j = 0; j < 3; ++j) p[k][j] = double(m.vertices[t[k]][j]) - o[j];
    }
    v += p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) - p[0][1] * (p[1][0] * p[2][2] - p[1][2] * p[2][0]) +
         p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]);
  }
  return v / 6.0;
}

inline const SceneMesh* find_mesh(const Scene& s, const std::string& name) {
  for (const SceneMesh& m : s.meshes) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

}  // namespace skyview::test
