#include "skyview/scene/scene.h"

#include <algorithm>
#include <limits>

namespace skyview {

std::array<Vec3f, 2> Scene::bounds() const {
  constexpr float inf = std::numeric_limits<float>::infinity();
  std::array<Vec3f, 2> b{Vec3f{inf, inf, inf}, Vec3f{-inf, -inf, -inf}};
  for (const SceneMesh& m : meshes) {
    for (const Vec3f& v : m.vertices) {
      for (int k = 0; k < 3; ++k) {
        b[0][k] = std::min(b[0][k], v[k]);
        b[1][k] = std::max(b[1][k], v[k]);
      }
    }
  }
  return b;
}

std::size_t Scene::triangle_count() const {
  std::size_t n = 0;
  for (const SceneMesh& m : meshes) n += m.triangles.size();
  return n;
}

}  // namespace skyview
