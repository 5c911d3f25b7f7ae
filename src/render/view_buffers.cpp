#include "skyview/render/view_buffers.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace skyview {

std::size_t ViewBuffers::hits() const {
  std::size_t n = 0;
  for (float d : depth.values()) n += !std::isnan(d);
  return n;
}

ViewBuffers render_view_buffers(const RayScene& scene, const Camera& camera) {
  ViewBuffers b;
  b.width = camera.width();
  b.height = camera.height();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::size_t n = static_cast<std::size_t>(b.width) * b.height;
  b.depth = Grid<float>(b.width, b.height, nan);
  b.position.assign(n, Vec3f{nan, nan, nan});
  b.normal.assign(n, Vec3f{nan, nan, nan});
  b.mesh.assign(n, std::numeric_limits<std::uint32_t>::max());
  tbb::parallel_for(0, b.height, [&](int row) {
    for (int col = 0; col < b.width; ++col) {
      const CameraRay r = camera.ray(col + 0.5, row + 0.5);
      const auto hit = scene.intersect(r.origin, r.direction);
      if (!hit) continue;
      const std::size_t i = b.depth.index(col, row);
      b.depth.values()[i] = hit->t;
      for (int k = 0; k < 3; ++k) b.position[i][k] = r.origin[k] + hit->t * r.direction[k];
      b.normal[i] = hit->normal;
      b.mesh[i] = hit->mesh;
    }
  });
  return b;
}

bool point_inside_scene(const RayScene& scene, const Vec3d& p, double touch) {
  const Vec3f origin{float(p[0]), float(p[1]), float(p[2])};
  // Straight up and four directions 30 degrees above the horizon, which a building's walls and
  // roof close and an open street, a courtyard or a porch's edge do not.
  std::vector<Vec3f> directions{{0, 0, 1}};
  for (int k = 0; k < 4; ++k) {
    const double a = k * std::numbers::pi / 2 + 0.3;
    directions.push_back({float(0.866 * std::cos(a)), float(0.866 * std::sin(a)), 0.5f});
  }
  int odd = 0;
  for (const Vec3f& d : directions) {
    int crossings = 0;
    float t = 0.0f;
    for (int guard = 0; guard < 1000; ++guard) {
      const auto hit = scene.intersect(origin, d, t);
      if (!hit) break;
      if (crossings == 0 && hit->t < touch) return true;
      ++crossings;
      t = hit->t + std::max(1e-4f, hit->t * 1e-6f);
    }
    odd += crossings % 2;
  }
  return 2 * odd > static_cast<int>(directions.size());
}

}  // namespace skyview
