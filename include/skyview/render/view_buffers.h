#pragma once
// What a camera sees of a scene, per pixel, from one primary ray each (Embree, in parallel): the
// G-buffer every screen-space pass reads (sky visibility here, shadows and sky colour later).
#include <cmath>
#include <cstdint>
#include <vector>

#include "skyview/core/grid.h"
#include "skyview/render/camera.h"
#include "skyview/scene/ray_scene.h"

namespace skyview {

struct ViewBuffers {
  int width = 0, height = 0;
  Grid<float> depth;                // distance along the ray, metres; NaN where the ray sees sky
  std::vector<Vec3f> position;      // scene-local hit point (NaN where sky)
  std::vector<Vec3f> normal;        // unit geometric normal, turned towards the camera (NaN where sky)
  std::vector<std::uint32_t> mesh;  // index into Scene::meshes (UINT32_MAX where sky)

  bool hit(std::size_t i) const { return !std::isnan(depth.values()[i]); }
  std::size_t hits() const;
};

// Casts one ray per pixel. Parallel over rows (oneTBB).
ViewBuffers render_view_buffers(const RayScene& scene, const Camera& camera);

// Whether a point lies inside a closed object: most of a few rays from it up and sideways upward
// cross the scene's surfaces an odd number of times (a point under a roof or a porch crosses them
// an even number of times, or none, on its way to the sky). Also true where a surface lies closer
// than `touch` metres in any of those directions.
bool point_inside_scene(const RayScene& scene, const Vec3d& local_point, double touch = 1e-3);

}  // namespace skyview
