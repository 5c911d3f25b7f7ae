#pragma once
// Embree's bounding-volume hierarchy over a Scene, for the rays camera views and shadows cast:
// nearest hits (primary rays: depth, normal, which object) and occlusion (shadow rays, sky
// visibility). Coordinates are the scene's own, relative to Scene::origin, in metres, z up.
// Queries are const and safe to call from many threads at once.
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>

#include "skyview/scene/scene.h"

namespace skyview {

struct RayHit {
  float t = 0;                 // distance along the (unit) direction
  Vec3f normal{0, 0, 1};       // unit geometric normal of the triangle, turned to face the ray's origin
  std::uint32_t mesh = 0;      // index into Scene::meshes
  std::uint32_t triangle = 0;  // index into that mesh's triangles
};

class RayScene {
 public:
  // Builds the hierarchy (robust build: rays along shared edges do not slip through). Throws
  // skyview::Error for an empty scene or if Embree fails.
  explicit RayScene(const Scene& scene);
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  // The nearest surface along origin + t·direction with t in (t_near, t_far); `direction` need
  // not be unit (t is then in its units).
  std::optional<RayHit> intersect(const Vec3f& origin, const Vec3f& direction, float t_near = 0.0f,
                                  float t_far = std::numeric_limits<float>::infinity()) const;

  // Whether any surface lies along origin + t·direction with t in (t_near, t_far).
  bool occluded(const Vec3f& origin, const Vec3f& direction, float t_near = 0.0f,
                float t_far = std::numeric_limits<float>::infinity()) const;

  // Bounds of the scene (relative to its origin), as Scene::bounds.
  const std::array<Vec3f, 2>& bounds() const { return bounds_; }

 private:
  struct Handles;
  std::unique_ptr<Handles> handles_;
  std::array<Vec3f, 2> bounds_;
};

}  // namespace skyview
