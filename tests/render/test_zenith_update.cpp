// Dynamic scenes: a zenith map updated inside a changed object's footprint equals a full build of
// the changed scene bit for bit, and a change that moves the map's frame is refused.
#include <gtest/gtest.h>

#include "render_test_support.h"
#include "skyview/render/zenith_depth_map.h"

using namespace skyview;
using namespace skyview::test;

namespace {

Scene street() {
  Scene s = porch_scene();
  s.meshes.push_back(box_mesh("house", {20, 20, 0}, {30, 30, 8}));
  s.meshes.push_back(box_mesh("shed", {-60, 30, 0}, {-52, 36, 4}));
  return s;
}

ZenithOptions options() {
  ZenithOptions o;
  o.resolution = 0.5;
  return o;
}

}  // namespace

TEST(RenderZenithUpdate, AddedObjectEqualsAFullBuild) {
  const Scene before = street();
  ZenithDepthMap map = ZenithDepthMap::build(before, RayScene(before), options());
  // A new porch-like object (slab on a post: layered texels) and a block.
  Scene after = before;
  after.meshes.push_back(box_mesh("canopy", {40, -20, 4}, {47.3f, -12.1f, 4.4f}));
  after.meshes.push_back(box_mesh("post", {40, -20, 0}, {40.3f, -19.7f, 4}));
  const RayScene rays(after);
  const ZenithDepthMap full = ZenithDepthMap::build(after, rays, options());
  ASSERT_FALSE(map.same_as(full));  // the change shows in the map
  const std::int64_t made = map.update_region(after, rays, options(), {40, -20}, {47.3, -12.1});
  EXPECT_GT(made, 15 * 16);
  EXPECT_LT(made, 20 * 20);
  EXPECT_TRUE(map.same_as(full));
  EXPECT_EQ(map.layered_texels(), full.layered_texels());
  EXPECT_GT(map.layered_texels(), 12 * 12 + 14 * 15);
}

TEST(RenderZenithUpdate, MovedObjectEqualsAFullBuild) {
  const Scene before = street();
  ZenithDepthMap map = ZenithDepthMap::build(before, RayScene(before), options());
  Scene after = before;
  after.meshes[after.meshes.size() - 2] = box_mesh("house", {-41.3f, 40.2f, 0}, {-30.1f, 51, 7.5f});
  const RayScene rays(after);
  const ZenithDepthMap full = ZenithDepthMap::build(after, rays, options());
  ASSERT_FALSE(map.same_as(full));
  // Where it was and where it is: two regions. The tallest object is lower now, but the rays' start
  // (rounded up to whole 16 m) stays.
  EXPECT_GT(map.update_region(after, rays, options(), {20, 20}, {30, 30}), 0);
  EXPECT_FALSE(map.same_as(full));
  EXPECT_GT(map.update_region(after, rays, options(), {-41.3, 40.2}, {-30.1, 51}), 0);
  EXPECT_TRUE(map.same_as(full));
  // A box outside the map makes nothing again.
  EXPECT_EQ(map.update_region(after, rays, options(), {1000, 1000}, {1010, 1010}), 0);
  EXPECT_TRUE(map.same_as(full));
}

TEST(RenderZenithUpdate, ChangesThatMoveTheFrameAreRefused) {
  const Scene before = street();
  const RayScene before_rays(before);
  ZenithDepthMap map = ZenithDepthMap::build(before, before_rays, options());
  const ZenithDepthMap copy = ZenithDepthMap::build(before, before_rays, options());
  // A tower above every roof: the rays would start higher.
  Scene taller = before;
  taller.meshes.push_back(box_mesh("tower", {50, 50, 0}, {55, 55, 40}));
  EXPECT_EQ(map.update_region(taller, RayScene(taller), options(), {50, 50}, {55, 55}), -1);
  // A block beyond the ground's edge: the grid grows.
  Scene wider = before;
  wider.meshes.push_back(box_mesh("far", {300, 0, 0}, {310, 10, 5}));
  EXPECT_EQ(map.update_region(wider, RayScene(wider), options(), {300, 0}, {310, 10}), -1);
  // Other options.
  ZenithOptions coarse = options();
  coarse.resolution = 1;
  EXPECT_EQ(map.update_region(before, before_rays, coarse, {0, 0}, {1, 1}), -1);
  EXPECT_TRUE(map.same_as(copy));
}
