// skyview render's passes against numbers: the camera's rays, the zenith map's layers, the canyon
// formula, the porch of the paper's Figure 4 against the ray-cast reference, a grazing plane.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "render_test_support.h"
#include "skyview/core/error.h"
#include "skyview/render/svf_reference.h"
#include "skyview/render/two_scale_visibility.h"

using namespace skyview;
using namespace skyview::test;

namespace {

struct Rendered {
  ViewBuffers view;
  TwoScaleBands bands;
  SvfReference reference;
};

Rendered render(const Scene& scene, const CameraSpec& spec, const TwoScaleOptions& o, int zenith_layers = 8,
                int reference_rays = 4096) {
  const RayScene rays(scene);
  const Camera camera(spec, scene.origin);
  ZenithOptions zo;
  zo.resolution = 0.5;
  zo.max_layers = zenith_layers;
  const ZenithDepthMap zenith = ZenithDepthMap::build(scene, rays, zo);
  Rendered r{render_view_buffers(rays, camera), {}, {}};
  r.bands = two_scale_visibility(r.view, camera, zenith, o);
  r.reference = svf_reference(rays, r.view, reference_rays);
  return r;
}

}  // namespace

TEST(RenderCamera, RaysAndProjectionAgree) {
  CameraSpec spec;
  spec.position = {100, 200, 30};
  spec.look_at = {110, 200, 30};
  spec.width = 81;
  spec.height = 61;
  const Camera cam(spec, {100, 200, 0});
  const CameraRay centre = cam.ray(40.5, 30.5);
  EXPECT_NEAR(centre.direction[0], 1.0, 1e-6);
  EXPECT_NEAR(centre.origin[2], 30.0, 1e-6);
  // The top row looks up by half the field of view.
  const CameraRay top = cam.ray(40.5, 0.0);
  EXPECT_NEAR(std::atan2(top.direction[2], top.direction[0]) * 180 / std::numbers::pi, 30.0, 1e-4);
  double col, row, depth;
  cam.project({0 + 20.0 * 3, 0 + 20.0 * -0.2, 30 + 20.0 * 0.1}, col, row, depth);
  const CameraRay back = cam.ray(col, row);
  EXPECT_NEAR(back.direction[1] / back.direction[0], -0.2 / 3, 1e-6);
  EXPECT_NEAR(back.direction[2] / back.direction[0], 0.1 / 3, 1e-6);
  EXPECT_NEAR(depth, 60.0, 1e-9);
}

TEST(RenderCamera, BadCamerasAreRefused) {
  CameraSpec spec;
  spec.position = {1, 2, 3};
  spec.look_at = {1, 2, 3};
  EXPECT_THROW(Camera(spec, {0, 0, 0}), UsageError);
  spec.look_at = {5, 2, 3};
  spec.fov_deg = 0;
  EXPECT_THROW(Camera(spec, {0, 0, 0}), UsageError);
  spec.fov_deg = 180;
  EXPECT_THROW(Camera(spec, {0, 0, 0}), UsageError);
  spec.fov_deg = 60;
  spec.up = {1, 0, 0};  // along the view
  EXPECT_THROW(Camera(spec, {0, 0, 0}), UsageError);
  int w, h;
  EXPECT_THROW(parse_size("800", w, h, "--size"), UsageError);
  EXPECT_THROW(parse_size("0x600", w, h, "--size"), UsageError);
  parse_size("640x480", w, h, "--size");
  EXPECT_EQ(w, 640);
  EXPECT_EQ(h, 480);
  EXPECT_THROW(parse_vec3("1,2", "--camera"), UsageError);
}

TEST(RenderZenith, LayersOnlyWhereARayMeetsTheSceneTwice) {
  Scene s = porch_scene();
  s.meshes.push_back(box_mesh("house", {20, 20, 0}, {30, 30, 8}));
  const RayScene rays(s);
  ZenithOptions zo;
  zo.resolution = 0.5;
  const ZenithDepthMap z = ZenithDepthMap::build(s, rays, zo);
  // Under the slab's middle: slab top, slab bottom, ground.
  const int c = z.col_of(0.1), r = z.row_of(0.1);
  ASSERT_EQ(z.count(c, r), 3);
  EXPECT_NEAR(z.heights(c, r)[0], 3.3, 1e-4);
  EXPECT_NEAR(z.heights(c, r)[1], 3.0, 1e-4);
  EXPECT_NEAR(z.heights(c, r)[2], 0.0, 1e-4);
  // In the open: the ground alone.
  EXPECT_EQ(z.count(z.col_of(50.1), z.row_of(0.1)), 1);
  // On the house: one solid from its roof down (its floor merges with the ground).
  ASSERT_EQ(z.count(z.col_of(25.1), z.row_of(25.1)), 1);
  EXPECT_NEAR(z.heights(z.col_of(25.1), z.row_of(25.1))[0], 8.0, 1e-4);
  EXPECT_EQ(z.layered_texels(), 12 * 12);  // the slab's texels (6 m at 0.5 m)
  EXPECT_EQ(z.deepest(), 3);
}

// Cosine-weighted svf at the centre line of a long canyon's floor: the sky between the wall tops
// seen under ±atan(W / 2H) from the zenith, svf = 1 / sqrt(1 + (2H/W)²) = cos(atan(2H/W)).
TEST(RenderVisibility, CanyonFloorMatchesTheCanyonFormula) {
  for (const auto& [width, height] : {std::pair{10.0f, 10.0f}, std::pair{20.0f, 8.0f}}) {
    const Scene s = canyon_scene(width, height, 2000);
    CameraSpec spec;
    spec.position = {0, 0, 50};
    spec.look_at = {0, 0, 0};
    spec.up = {0, 1, 0};
    spec.orthographic_width = 4;
    spec.width = spec.height = 21;
    TwoScaleOptions o;
    const Rendered r = render(s, spec, o);
    const std::size_t i = r.view.depth.index(10, 10);
    ASSERT_NEAR(r.view.depth.values()[i], 50.0, 1e-3);
    const double formula = std::cos(std::atan(2.0 * height / width));
    EXPECT_NEAR(r.bands.svf_large.values()[i], formula, 0.03) << "W " << width << " H " << height;
    EXPECT_NEAR(r.bands.svf_fine.values()[i], 1.0, 1e-6);  // nothing within the fine radius
    EXPECT_NEAR(r.reference.svf.values()[i], formula, 4 * r.reference.stderr_.values()[i] + 1e-3);
  }
}

// The paper's Figure 4: under a porch the opening angle lets in the sky below the slab's edge,
// which a single-layer (height field) zenith map hides.
TEST(RenderVisibility, PorchGetsMoreSkyWithTheOpeningAngle) {
  const Scene s = porch_scene();
  CameraSpec spec;
  spec.position = {-20, 0.5, 1.5};
  spec.look_at = {0, 0.5, 0};
  spec.width = 41;
  spec.height = 31;
  spec.fov_deg = 20;
  TwoScaleOptions o;
  const Rendered layered = render(s, spec, o);
  const Rendered flat = render(s, spec, o, 1, 16);
  const std::size_t i = layered.view.depth.index(20, 15);
  const auto& p = layered.view.position[i];
  ASSERT_LT(std::abs(p[0]), 1.0f);
  ASSERT_NEAR(p[2], 0.0f, 1e-3f);
  const double reference = layered.reference.svf.values()[i];
  const double opened = layered.bands.svf_large.values()[i];
  const double closed = flat.bands.svf_large.values()[i];
  EXPECT_GT(opened, closed + 0.2);
  EXPECT_LT(closed, 0.05);
  EXPECT_NEAR(opened, reference, 0.08) << "closed " << closed;
  EXPECT_GT(reference, 0.35);
  EXPECT_LT(reference, 0.65);
}

TEST(RenderVisibility, GrazingPlaneStaysInRange) {
  Scene s;
  s.meshes.push_back(ground_mesh(600));
  CameraSpec spec;
  spec.position = {0, 0, 0.5};
  spec.look_at = {500, 0, 0};
  spec.width = 64;
  spec.height = 48;
  spec.fov_deg = 10;
  TwoScaleOptions o;
  o.combine = ScaleCombination::intersect;
  const Rendered r = render(s, spec, o, 8, 64);
  ASSERT_GT(r.view.hits(), 100u);
  for (std::size_t i = 0; i < r.view.position.size(); ++i) {
    if (!r.view.hit(i)) continue;
    for (const Grid<float>* g : {&r.bands.svf, &r.bands.svf_large, &r.bands.svf_fine}) {
      const float v = g->values()[i];
      ASSERT_TRUE(std::isfinite(v));
      ASSERT_GE(v, 0.0f);
      ASSERT_LE(v, 1.0f);
    }
    EXPECT_GT(r.bands.svf.values()[i], 0.95f);  // an open plane sees the whole sky
  }
}

TEST(RenderVisibility, CameraInsideABoxIsDetected) {
  Scene s = porch_scene();
  s.meshes.push_back(box_mesh("house", {20, 20, 0}, {30, 30, 8}));
  const RayScene rays(s);
  EXPECT_TRUE(point_inside_scene(rays, {25, 25, 4}));
  EXPECT_FALSE(point_inside_scene(rays, {0, 0, 1.5}));  // under the porch
  EXPECT_FALSE(point_inside_scene(rays, {40, 25, 4}));  // beside the house
  EXPECT_TRUE(point_inside_scene(rays, {25, 25, 8}));   // on its roof: touching
}

TEST(RenderVisibility, CosineWeightedSliceSums) {
  // A horizontal surface open to the zenith in every direction sees the whole sky.
  const int n = 16;
  double sum = 0, wall = 0;
  for (int k = 0; k < n; ++k) {
    const double az = 2 * std::numbers::pi * (k + 0.5) / n;
    sum += 2.0 / n * cosine_weighted_slice(0, 1, 0, std::numbers::pi / 2);
    wall += 2.0 / n * cosine_weighted_slice(std::cos(az), 0, 0, std::numbers::pi / 2);
  }
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_NEAR(wall, 0.5, 0.01);  // a wall sees half the sky
}
