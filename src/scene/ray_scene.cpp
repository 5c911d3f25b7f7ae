#include "skyview/scene/ray_scene.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/embree_device.h"
#include "skyview/core/error.h"

namespace skyview {

struct RayScene::Handles {
  std::string failure;  // first Embree error; declared before the device that writes it
  detail::EmbreeDevice device;
  detail::EmbreeScene scene;
};

RayScene::RayScene(const Scene& scene) : handles_(std::make_unique<Handles>()), bounds_(scene.bounds()) {
  if (scene.triangle_count() == 0) throw Error("the scene has no triangles to cast rays at");
  Handles& h = *handles_;
  h.device = detail::new_embree_device(h.failure, /*need_filters=*/false);
  h.scene.reset(rtcNewScene(h.device.get()));
  rtcSetSceneFlags(h.scene.get(), RTC_SCENE_FLAG_ROBUST);
  // One geometry per mesh, with the mesh's index as its id, so a hit names its object.
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    const SceneMesh& mesh = scene.meshes[m];
    RTCGeometry geom = rtcNewGeometry(h.device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    const std::size_t nv = std::max<std::size_t>(mesh.vertices.size(), 1);
    auto* v = static_cast<float*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
    std::fill(v, v + 3 * nv, 0.0f);
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
      std::copy(mesh.vertices[i].begin(), mesh.vertices[i].end(), v + 3 * i);
    // An empty mesh keeps its id with one degenerate triangle, which no ray meets.
    const std::size_t nt = std::max<std::size_t>(mesh.triangles.size(), 1);
    auto* ib = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), nt));
    std::fill(ib, ib + 3 * nt, 0u);
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
      std::copy(mesh.triangles[i].begin(), mesh.triangles[i].end(), ib + 3 * i);
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(h.scene.get(), geom, static_cast<unsigned>(m));
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(h.scene.get());
  if (!h.failure.empty()) throw Error(h.failure);
}

RayScene::~RayScene() = default;

namespace {

RTCRay ray_of(const Vec3f& o, const Vec3f& d, float t_near, float t_far) {
  RTCRay ray{};
  ray.org_x = o[0];
  ray.org_y = o[1];
  ray.org_z = o[2];
  ray.dir_x = d[0];
  ray.dir_y = d[1];
  ray.dir_z = d[2];
  ray.tnear = t_near;
  ray.tfar = t_far;
  ray.mask = 0xFFFFFFFFu;
  return ray;
}

}  // namespace

std::optional<RayHit> RayScene::intersect(const Vec3f& origin, const Vec3f& direction, float t_near,
                                          float t_far) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray = ray_of(origin, direction, t_near, t_far);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(handles_->scene.get(), &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  RayHit hit;
  hit.t = rh.ray.tfar;
  hit.mesh = rh.hit.geomID;
  hit.triangle = rh.hit.primID;
  float n[3] = {rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z};
  const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  const float facing = n[0] * direction[0] + n[1] * direction[1] + n[2] * direction[2] > 0 ? -1.0f : 1.0f;
  if (length > 0) hit.normal = {facing * n[0] / length, facing * n[1] / length, facing * n[2] / length};
  return hit;
}

bool RayScene::occluded(const Vec3f& origin, const Vec3f& direction, float t_near, float t_far) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray = ray_of(origin, direction, t_near, t_far);
  rtcOccluded1(handles_->scene.get(), &context, &ray);
  return ray.tfar < 0;  // Embree sets tfar to -inf when the ray is blocked
}

}  // namespace skyview
