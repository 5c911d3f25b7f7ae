// The exposure reference of skyview render (an hourly sky cast with exact rays) against the
// map's own integral on an open plane, and the two-scale exposure band against it on a canyon's
// floor.
#include <gtest/gtest.h>

#include <cmath>

#include "render_test_support.h"
#include "skyview/render/exposure_reference.h"
#include "skyview/render/two_scale_visibility.h"
#include "skyview/sky/exposure_pyramid.h"
#include "skyview/sky/exposure_steps.h"
#include "skyview/sky/sky_models.h"
#include "skyview/solar/time_parse.h"

using namespace skyview;
using namespace skyview::test;

namespace {

// A year at 52° N with two-hour steps of a Preetham clear sky on a 128 × 128 map.
const ExposureMap& year_map() {
  static const ExposureMap map = [] {
    Site site;
    site.latitude_deg = 52.0;
    site.longitude_deg = 13.0;
    const auto steps =
        regular_steps(site, parse_time("2023-01-01T00:00Z").unix_utc, parse_time("2024-01-01T00:00Z").unix_utc, 7200.0);
    ExposureOptions o;
    o.width = o.height = 128;
    return integrate_exposure(*make_preetham_sky(3.0), steps, o);
  }();
  return map;
}

CameraSpec looking_down(double width) {
  CameraSpec spec;
  spec.position = {0, 0, 50};
  spec.look_at = {0, 0, 0};
  spec.up = {0, 1, 0};
  spec.orthographic_width = width;
  spec.width = spec.height = 5;
  return spec;
}

}  // namespace

// An open plane sees the whole sky: the reference is the map's global horizontal total.
TEST(RenderExposureReference, OpenPlaneGetsTheMapsHorizontalTotal) {
  Scene s;
  s.meshes.push_back(ground_mesh(100));
  const RayScene rays(s);
  const Camera camera(looking_down(4), s.origin);
  const ViewBuffers view = render_view_buffers(rays, camera);
  const ExposureMap& map = year_map();
  const double total = map.irradiation(ExposureBand::global, {0, 0, 1}) / 1000;  // kWh m-2
  ASSERT_GT(total, 500);
  const ExposureReference ref = exposure_reference(rays, view, map, 1024);
  for (std::size_t i = 0; i < view.position.size(); ++i) {
    ASSERT_TRUE(view.hit(i));
    const double se = ref.stderr_.values()[i];
    EXPECT_GT(se, 0);
    EXPECT_LT(se, 0.04 * total);  // the two strategies together keep the noise low (about 2.7 %)
    // Within 4 standard errors plus the map's cell-centre cosine (under 0.5 %).
    EXPECT_NEAR(ref.exposure.values()[i], total, 4 * se + 0.005 * total) << "pixel " << i;
  }
}

// The floor of a north-south canyon (H = W = 10 m): the two-scale exposure band (16 × (16 + 16),
// Eqs. 7–10) agrees with the exposure reference within 3 % plus four standard errors (measured: 705 against
// 690 ± 12 kWh m-2 at 16384 rays; the open plane gets 2242), and both lie
// far below the open plane's total.
TEST(RenderExposureReference, CanyonFloorAgreesWithTheExposureBand) {
  const Scene s = canyon_scene(10, 10, 1000);
  const RayScene rays(s);
  const Camera camera(looking_down(4), s.origin);
  const ViewBuffers view = render_view_buffers(rays, camera);
  ZenithOptions zo;
  zo.resolution = 0.5;
  const ZenithDepthMap zenith = ZenithDepthMap::build(s, rays, zo);
  const ExposureMap& map = year_map();
  const ExposurePyramid pyramid(map);
  TwoScaleOptions o;
  const ExposureSampler sampler(pyramid, o.directions, 0.0, SamplerOptions{});
  const TwoScaleBands bands = two_scale_visibility(view, camera, zenith, o, &sampler);
  const ExposureReference ref = exposure_reference(rays, view, map, 16384);
  const double open = map.irradiation(ExposureBand::global, {0, 0, 1}) / 1000;
  const std::size_t centre = view.depth.index(2, 2);
  const double reference = ref.exposure.values()[centre], se = ref.stderr_.values()[centre];
  EXPECT_LT(reference, 0.8 * open);
  EXPECT_GT(reference, 0.2 * open);
  EXPECT_NEAR(bands.exposure.values()[centre], reference, 0.03 * reference + 4 * se)
      << "band " << bands.exposure.values()[centre] << " reference " << reference << " +- " << se << " open " << open;
}
