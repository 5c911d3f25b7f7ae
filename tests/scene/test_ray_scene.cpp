// RayScene against geometry whose answers are known: a 10 m ground square and a 2 m cube on it.
#include <gtest/gtest.h>

#include "skyview/core/error.h"
#include "skyview/scene/ray_scene.h"

namespace skyview {
namespace {

Scene ground_and_cube() {
  Scene s;
  SceneMesh ground{"ground", "test", {{-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}}, {{0, 1, 2}, {0, 2, 3}}};
  SceneMesh cube{"cube", "test", {}, {}};
  for (int i = 0; i < 8; ++i)
    cube.vertices.push_back(
        {static_cast<float>(i & 1) * 2, static_cast<float>((i >> 1) & 1) * 2, static_cast<float>((i >> 2) & 1) * 2});
  // Two triangles per face, vertex index bits: x = 1, y = 2, z = 4.
  cube.triangles = {{0, 1, 3}, {0, 3, 2}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                    {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 3, 7}, {1, 7, 5}};
  s.meshes = {ground, cube};
  return s;
}

TEST(RayScene, NearestHitsGiveDistanceNormalAndObject) {
  const RayScene rays(ground_and_cube());
  const auto top = rays.intersect({1, 1, 10}, {0, 0, -1});
  ASSERT_TRUE(top);
  EXPECT_FLOAT_EQ(top->t, 8.0f);
  EXPECT_EQ(top->mesh, 1u);
  EXPECT_FLOAT_EQ(top->normal[2], 1.0f);
  const auto floor = rays.intersect({-3, 1, 10}, {0, 0, -1});
  ASSERT_TRUE(floor);
  EXPECT_FLOAT_EQ(floor->t, 10.0f);
  EXPECT_EQ(floor->mesh, 0u);
  // The west face seen from the west: its normal is turned towards the eye whatever the winding.
  const auto side = rays.intersect({-4, 1, 1}, {1, 0, 0});
  ASSERT_TRUE(side);
  EXPECT_FLOAT_EQ(side->t, 4.0f);
  EXPECT_FLOAT_EQ(side->normal[0], -1.0f);
  EXPECT_FALSE(rays.intersect({-4, 1, 1}, {-1, 0, 0}));
  EXPECT_FALSE(rays.intersect({-4, 1, 1}, {1, 0, 0}, 0.0f, 3.9f));  // t_far stops short of the face
}

TEST(RayScene, OcclusionOfShadowRays) {
  const RayScene rays(ground_and_cube());
  // A point on the ground east of the cube, sun low in the west: shadowed; sun in the east: lit.
  EXPECT_TRUE(rays.occluded({3, 1, 0.01f}, {-1, 0, 0.2f}));
  EXPECT_FALSE(rays.occluded({3, 1, 0.01f}, {1, 0, 0.2f}));
  // Steep enough to clear the cube's top edge (2 m high, 1 m away, slope > 2).
  EXPECT_FALSE(rays.occluded({3, 1, 0.01f}, {-1, 0, 2.5f}));
  EXPECT_EQ(rays.bounds()[1][2], 2.0f);
}

TEST(RayScene, AnEmptySceneIsRefused) {
  Scene empty;
  EXPECT_THROW(RayScene{empty}, Error);
}

}  // namespace
}  // namespace skyview
