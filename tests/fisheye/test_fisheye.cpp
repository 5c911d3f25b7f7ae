// Fish-eye projections, sky fractions, the round trip from skyview's own masks to the point
// queries, a synthetic photograph and the real photographs of ../shared/sample_data/fisheye.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "core/test_support.h"
#include "skyview/core/error.h"
#include "skyview/fisheye/fisheye_svf.h"
#include "skyview/fisheye/fisheye_view.h"

namespace skyview {
namespace {

using test::kDeg;

TEST(FisheyeProjection, EachMapsZenithAngleToRadiusAsItsFormulaSays) {
  // r / R at 0, 30, 60, 90 degrees, from the formulas written out.
  const double equidistant[] = {0, 1.0 / 3, 2.0 / 3, 1};
  const double equisolid[] = {0, std::sqrt(2.0) * std::sin(15 * kDeg), std::sqrt(2.0) * 0.5, 1};
  const double orthographic[] = {0, 0.5, std::sqrt(3.0) / 2, 1};
  const double stereographic[] = {0, std::tan(15 * kDeg), 1 / std::sqrt(3.0), 1};
  const double* expected[] = {equidistant, equisolid, orthographic, stereographic};
  const Projection all[] = {Projection::equidistant, Projection::equisolid, Projection::orthographic,
                            Projection::stereographic};
  for (int p = 0; p < 4; ++p) {
    for (int i = 0; i < 4; ++i) {
      const double t = i * 30 * kDeg;
      EXPECT_NEAR(projection_radius(all[p], t), expected[p][i], 1e-12) << projection_name(all[p]) << " " << i * 30;
      EXPECT_NEAR(projection_zenith(all[p], expected[p][i]), t, 1e-9) << projection_name(all[p]);
    }
    EXPECT_EQ(projection_named(projection_name(all[p])), all[p]);
  }
  EXPECT_THROW(projection_named("fisheye"), Error);
}

TEST(FisheyeProjection, NorthIsUpAndEastLeftAsACameraLookingUpSeesIt) {
  FisheyeFrame f{100, 100, 100, Projection::equidistant, false};
  double x, y, zenith, azimuth;
  f.pixel(M_PI / 2, 0.0, x, y);  // north on the horizon: top
  EXPECT_NEAR(x, 100, 1e-9);
  EXPECT_NEAR(y, 0, 1e-9);
  f.pixel(M_PI / 2, M_PI / 2, x, y);  // east: left
  EXPECT_NEAR(x, 0, 1e-9);
  EXPECT_NEAR(y, 100, 1e-9);
  ASSERT_TRUE(f.direction(150, 100, zenith, azimuth));  // right of centre: west, 45° from the zenith
  EXPECT_NEAR(azimuth, 270 * kDeg, 1e-9);
  EXPECT_NEAR(zenith, 45 * kDeg, 1e-9);
  f.mirror = true;
  f.pixel(M_PI / 2, M_PI / 2, x, y);  // mirrored: east on the right
  EXPECT_NEAR(x, 200, 1e-9);
  EXPECT_FALSE(f.direction(0, 0, zenith, azimuth)) << "the corner is beyond 90 degrees";
}

// A mask whose horizon stands at elevation e all round: svf = cos²e, sky visibility = 1 − sin e.
TEST(SkyFractions, ConstantHorizonGivesTheAnalyticValuesInEveryProjection) {
  const int size = 601;
  for (Projection p :
       {Projection::equidistant, Projection::equisolid, Projection::orthographic, Projection::stereographic}) {
    const FisheyeFrame f{300, 300, 300, p, false};
    for (double e : {0.0, 20.0, 45.0, 70.0}) {
      std::vector<std::uint8_t> sky(size * size, 0);
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          double zenith, azimuth;
          if (f.direction(x, y, zenith, azimuth) && 90 * kDeg - zenith > e * kDeg) sky[y * size + x] = 255;
        }
      const SkyFractions s = sky_fractions(sky, size, size, f, 36);
      const double a = e * kDeg;
      EXPECT_NEAR(s.svf, std::cos(a) * std::cos(a), 0.002) << projection_name(p) << " " << e;
      // The orthographic projection packs the solid angle near the horizon into its rim, where pixels
      // cut by the 90° circle count part of it: 0.021 short of an open sky at a 300 px radius.
      EXPECT_NEAR(s.sky_visibility, 1 - std::sin(a), p == Projection::orthographic ? 0.025 : 0.002)
          << projection_name(p) << " " << e;
      // Steyn's midpoint weights read an open sky as (π/72)/sin(π/72) = 1.000317 at 36 rings, and a
      // constant horizon within 0.0004 of cos²e (docs/fisheye.md); pixels add their own.
      EXPECT_NEAR(s.svf_annulus, std::cos(a) * std::cos(a), 0.002) << projection_name(p) << " " << e;
    }
  }
}

FisheyeImage mask_image(const FisheyeView& v) { return {v.size, v.size, 1, v.mask}; }

// Skyview's own mask read back by fisheye-svf against the point query's svf at the same observer.
void expect_round_trip(const Terrain& t, const Observer& o, const std::string& what, double* worst_exact,
                       double* worst_annulus) {
  FisheyeViewOptions vo;
  vo.size = 512;
  vo.horizons.params.curvature = "off";
  vo.annotate = false;
  const FisheyeView view = fisheye_view(t, o, vo);
  ASSERT_TRUE(view.problem.empty()) << view.problem;
  FisheyeSvfOptions so;
  so.threshold = SkyThreshold::mask;
  const FisheyeSvfResult r = fisheye_svf(mask_image(view), so);
  PointHorizonOptions po;
  po.params.directions = 64;
  po.params.curvature = "off";
  const PointHorizons ph = point_horizons(t, {o}, po);
  const double svf = point_sky_view(t, o, ph.of(0), 64, ph.sector_rotation).svf;
  EXPECT_NEAR(r.fractions.svf, svf, 0.01) << what;
  EXPECT_NEAR(r.fractions.svf_annulus, svf, 0.01) << what;
  *worst_exact = std::max(*worst_exact, std::abs(r.fractions.svf - svf));
  *worst_annulus = std::max(*worst_annulus, std::abs(r.fractions.svf_annulus - svf));
}

TEST(FisheyeRoundTrip, MaskReadBackAgreesWithThePointQueryOnCanyonPitAndCity) {
  double exact = 0, annulus = 0;
  const Terrain canyon = rasterize(street_canyon(10, 20), 41, 801, local_grid(41, 801, 1.0));
  expect_round_trip(canyon, {20.0, 400.0, 1.1}, "canyon centreline", &exact, &annulus);
  expect_round_trip(canyon, {22.3, 400.5, 1.1}, "canyon off centre", &exact, &annulus);
  const Terrain pit = rasterize(circular_pit(20, 15), 61, 61, local_grid(61, 61, 1.0));
  expect_round_trip(pit, {30.0, 30.0, 1.1}, "pit", &exact, &annulus);
  const std::string city_path = std::string(SKYVIEW_SOURCE_DIR) + "/sample_dems/city.tif";
  const Terrain city = read_terrain(city_path, {});
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> pos(20.0, 380.0);
  for (int i = 0; i < 20; ++i) {
    expect_round_trip(city, {pos(rng), pos(rng), 1.1}, "city point " + std::to_string(i), &exact, &annulus);
  }
  std::printf("round trip: worst |svf - points| %.4f (exact weights), %.4f (annulus, 36 rings)\n", exact, annulus);
}

// A synthetic photograph: black border, a circle of blue sky with noise, grey buildings.
TEST(FisheyePhotograph, SyntheticPhotoIsClassifiedAndItsCircleFound) {
  const int w = 480, h = 360;
  const double cx = 241.4, cy = 176.7, radius = 160.0;
  FisheyeImage im{w, h, 3, std::vector<std::uint8_t>(w * h * 3, 0)};
  std::vector<std::uint8_t> truth(w * h, 0);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0, 6);
  auto clamp8 = [](double v) { return static_cast<std::uint8_t>(std::clamp(v, 0.0, 255.0)); };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = im.pixels.data() + (y * w + x) * 3;
      p[0] = clamp8(2 + noise(rng) / 3), p[1] = clamp8(2 + noise(rng) / 3), p[2] = clamp8(2 + noise(rng) / 3);
      if (std::hypot(x - cx, y - cy) > radius) continue;
      // Buildings: two blocks from the rim and a tower.
      const bool building = (x < cx - 60) || (y > cy + 90) || (x > cx + 40 && x < cx + 80 && y < cy - 20);
      if (building) {
        const double g = 95 + noise(rng);
        p[0] = clamp8(g), p[1] = clamp8(g), p[2] = clamp8(g + 5);
      } else {
        p[0] = clamp8(70 + noise(rng)), p[1] = clamp8(130 + noise(rng)), p[2] = clamp8(215 + noise(rng));
        truth[y * w + x] = 255;
      }
    }
  }
  const FisheyeSvfResult r = fisheye_svf(im, {});
  EXPECT_NEAR(r.circle.cx, cx, 2.0);
  EXPECT_NEAR(r.circle.cy, cy, 2.0);
  EXPECT_NEAR(r.circle.radius, radius, 2.0);
  long long sky = 0, agree = 0, wrong = 0;
  for (int i = 0; i < w * h; ++i) {
    sky += truth[i] != 0;
    agree += truth[i] != 0 && r.classification.sky[i] != 0;
    wrong += truth[i] == 0 && r.classification.sky[i] != 0;
  }
  EXPECT_LT(std::abs(double(agree + wrong - sky)), 0.01 * sky) << "sky pixels within 1%";
  EXPECT_GT(agree, 0.99 * sky);
}

TEST(FisheyePhotograph, ImagesWithoutACircleAreRefused) {
  FisheyeImage grey{200, 200, 3, std::vector<std::uint8_t>(200 * 200 * 3, 128)};
  EXPECT_THROW(find_image_circle(grey), Error);
  FisheyeImage black{200, 200, 3, std::vector<std::uint8_t>(200 * 200 * 3, 0)};
  EXPECT_THROW(find_image_circle(black), Error);
}

// The real photographs (../shared/sample_data/fisheye/SOURCE.md): circles found automatically
// where the rim shows against the black border, svf plausible for each scene, clouds as sky.
TEST(FisheyePhotograph, RealPhotographsGivePlausibleSvf) {
  const std::string dir = std::string(SKYVIEW_SHARED_DIR) + "/sample_data/fisheye/";
  if (!std::filesystem::exists(dir + "rcaiman_DSCN5547.JPG")) GTEST_SKIP() << "no fish-eye samples in " << dir;
  struct Case {
    const char* file;
    double cx, cy, radius, tolerance;  // expected circle (SOURCE.md's published or estimated values)
    double svf_lo, svf_hi;
  };
  const Case found[] = {
      {"rcaiman_DSCN5547.JPG", 1270, 974, 781, 12, 0.90, 1.0},  // clearing: open sky (SOURCE.md estimate)
      // Forest edge, a crown over half the sky: the published zenith, 95° at 745 * 95 / 90 px.
      {"rcaiman_DSCN5548.JPG", 1280, 960, 786, 15, 0.10, 0.40},
      {"HorizonPy_Horizon_3.JPG", 2431, 1662, 1540, 25, 0.70, 0.90},  // ridge over a third
      // Dark conifer canopy with a central gap: rcaiman's zenith and 95° circle; the rim shows only
      // where sky reaches it.
      {"rcaiman_DSCN4500.JPG", 1276, 980, 793, 40, 0.05, 0.30},
      // Under-exposed chestnut canopy: hemispheR's centre; 754 px is its 90° radius of a 183° lens.
      {"hemispheR_circular_coolpix4500+FC-E8_chestnut.jpg", 1136, 852, 767, 30, 0.02, 0.15}};
  for (const Case& c : found) {
    const FisheyeSvfResult r = fisheye_svf(read_fisheye_image(dir + c.file), {});
    EXPECT_TRUE(r.circle_found);
    EXPECT_NEAR(r.circle.cx, c.cx, c.tolerance) << c.file;
    EXPECT_NEAR(r.circle.cy, c.cy, c.tolerance) << c.file;
    EXPECT_NEAR(r.circle.radius, c.radius, c.tolerance) << c.file;
    EXPECT_GT(r.fractions.svf, c.svf_lo) << c.file;
    EXPECT_LT(r.fractions.svf, c.svf_hi) << c.file;
  }
  // Under-exposed canopy with the published circle: hemispheR's DIFN is 6.19 % (0-75°).
  FisheyeSvfOptions chestnut;
  chestnut.circle = ImageCircle{1136, 852, 754, 0, 0, 0};
  const FisheyeSvfResult r =
      fisheye_svf(read_fisheye_image(dir + "hemispheR_circular_coolpix4500+FC-E8_chestnut.jpg"), chestnut);
  EXPECT_GT(r.fractions.svf, 0.02);
  EXPECT_LT(r.fractions.svf, 0.15);
  // A full-frame fish-eye has no circle: refused, with the way out named.
  try {
    find_image_circle(read_fisheye_image(dir + "hemispheR_fullframe_D90_Nikkor-10.5_beech.jpg"));
    ADD_FAILURE() << "a full-frame photograph has no image circle";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--center and --radius"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace skyview
