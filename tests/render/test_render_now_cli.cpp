// `skyview render --time` beyond the sun's beam: the diffuse sky at the instant through the view's
// visible sky (diffuse_now, global_now), the view in colour (--colour-out: sky, sun disc, lit
// surfaces under one fixed tone mapping) and a shadow map's error against exact rays in the
// metadata (--shadow-diff draws it). The sky colour itself is checked against Preetham's published
// zenith chromaticity in tests/sky/test_sky_colour.cpp; here, that the render shows it.
#include <gdal_priv.h>

#include <cmath>
#include <numbers>
#include <string>

#include "core/cli_run.h"
#include "render_test_support.h"
#include "skyview/raster/raster_read.h"
#include "skyview/render/camera.h"
#include "skyview/render/shadow_error.h"
#include "skyview/render/shadow_maps.h"
#include "skyview/render/view_buffers.h"
#include "skyview/scene/ray_scene.h"
#include "skyview/sky/exposure_steps.h"
#include "skyview/sky/sky_colour.h"
#include "skyview/sky/sky_models.h"
#include "skyview/solar/solar_position.h"
#include "skyview/solar/time_parse.h"
#include "temp_dir.h"

using namespace skyview;
using namespace skyview::test;

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
// Munich, an equinox morning: the sun at about 115° azimuth, 26° elevation; turbidity 3 (default).
const char* kTime = "2024-03-20T08:00Z";
const char* kSun = " --time 2024-03-20T08:00Z --lat 48 --lon 11 --elevation 0";
const char* kView = " --camera 0,0,300 --look-at 0,0,0 --up 0,1,0 --orthographic 160 --size 320x320";

std::string write_scene(const std::string& dir, bool box) {
  Scene s;
  s.meshes.push_back(ground_mesh(200));
  if (box) s.meshes.push_back(box_mesh("box", {-5, -5, 0}, {5, 5, 20}));
  const std::string path = dir + (box ? "/box.obj" : "/plane.obj");
  write_obj(s, path);
  return path;
}

std::string metadata(const std::string& path, const char* key) {
  init_gdal();
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER));
  const char* v = ds ? ds->GetMetadataItem(key) : nullptr;
  return v ? v : "";
}

SunPosition munich_sun() { return solar_position(parse_time(kTime).unix_utc, Site{48.0, 11.0, 0.0}); }

struct Rgb {
  int r, g, b;
  int sum() const { return r + g + b; }
};

Rgb pixel(const std::string& png, int col, int row) {
  const RasterBand r = read_band(png, 1), g = read_band(png, 2), b = read_band(png, 3);
  return {int(r.values(col, row)), int(g.values(col, row)), int(b.values(col, row))};
}

}  // namespace

// An open plane sees the whole sky: its diffuse_now is the model's diffuse horizontal irradiance
// (Preetham, T = 3, at the instant), read from the instant's exposure map through the two-scale
// visibility. The map's 256 rows and the sampler's area reads keep it within 0.5 %.
TEST(RenderNowCli, OpenPlaneGetsTheSkysDiffuseHorizontalIrradiance) {
  const std::string dir = temp_dir("render-now");
  const std::string obj = write_scene(dir, false), out = dir + "/plane.tif";
  const RunResult r = run_skyview("render " + obj + " " + out + kView + kSun + " --zenith-res 2", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_band(out, 6).description, "diffuse_now");
  EXPECT_EQ(read_band(out, 6).unit, "W m-2");
  EXPECT_EQ(read_band(out, 7).description, "global_now");
  EXPECT_EQ(read_band(out, 8).description, "depth");
  const SunPosition sun = munich_sun();
  SkyConditions c;
  c.sun_zenith = sun.zenith_deg * kDegree;
  c.sun_azimuth = sun.azimuth_deg * kDegree;
  c.day_of_year = day_of_year_utc(parse_time(kTime).unix_utc);
  const double dhi = make_preetham_sky(3.0)->at(c)->diffuse_horizontal(360);
  ASSERT_GT(dhi, 50.0);
  EXPECT_NEAR(std::stod(metadata(out, "DIFFUSE_HORIZONTAL_W_M2")), dhi, 0.1 + 1e-3 * dhi);
  const RasterBand direct = read_band(out, 5), diffuse = read_band(out, 6), global = read_band(out, 7);
  for (int row : {20, 160, 300}) {
    for (int col : {20, 160, 300}) {
      EXPECT_NEAR(diffuse.values(col, row), dhi, 0.005 * dhi) << col << "," << row;
      EXPECT_NEAR(global.values(col, row), direct.values(col, row) + diffuse.values(col, row), 1e-3);
    }
  }
}

// The sky is brightest around the sun: at 08:00 (sun at about 115° azimuth) the box's east wall gets
// more diffuse light than its west wall (the map's azimuths agree with the view's), and only the
// east wall gets the beam.
TEST(RenderNowCli, WallFacingTheSunsSideOfTheSkyGetsMoreDiffuseLight) {
  const std::string dir = temp_dir("render-now");
  const std::string obj = write_scene(dir, true);
  float diffuse[2], direct[2];
  for (int side = 0; side < 2; ++side) {
    const std::string out = dir + (side ? "/west.tif" : "/east.tif");
    const std::string x = side ? "-100" : "100";
    const RunResult r = run_skyview("render " + obj + " " + out + " --camera " + x + ",0,10 --look-at 0,0,10" +
                                        " --size 21x21 --fov 10 --zenith-res 1" + kSun,
                                    dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    direct[side] = read_band(out, 5).values(10, 10);
    diffuse[side] = read_band(out, 6).values(10, 10);
  }
  EXPECT_GT(direct[0], 300.0f);
  EXPECT_EQ(direct[1], 0.0f);
  EXPECT_GT(diffuse[0], 1.5f * diffuse[1]) << diffuse[0] << " east, " << diffuse[1] << " west";
  EXPECT_GT(diffuse[1], 20.0f);
}

// With --skymap the visibility pass reads the period's map and a second pass with the same seed
// reads the instant's: diffuse_now is the same as without --skymap, to the bit, and the box's
// neighbourhood (where the regions matter) is in view.
TEST(RenderNowCli, DiffuseNowIsTheSameWithAndWithoutASkymap) {
  const std::string dir = temp_dir("render-now");
  const std::string obj = write_scene(dir, true), map = dir + "/sky.tif";
  ASSERT_EQ(run_skyview("skymap " + map +
                            " --no-preview --lat 48 --lon 11 --from 2024-06-21T00:00Z --to 2024-06-22T00:00Z --step 1h "
                            "--size 64",
                        dir)
                .exit_code,
            0);
  const std::string small =
      " --camera 0,0,300 --look-at 0,0,0 --up 0,1,0 --orthographic 60 --size 60x60 --zenith-res 1";
  RunResult r = run_skyview("render " + obj + " " + dir + "/a.tif" + small + kSun, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_skyview("render " + obj + " " + dir + "/b.tif" + small + kSun + " --skymap " + map, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RasterBand a = read_band(dir + "/a.tif", 6), b = read_band(dir + "/b.tif", 9);
  ASSERT_EQ(a.description, "diffuse_now");
  ASSERT_EQ(b.description, "diffuse_now");
  float low = 1e9f, high = 0;
  for (int row = 0; row < 60; ++row) {
    for (int col = 0; col < 60; ++col) {
      ASSERT_EQ(a.values(col, row), b.values(col, row)) << col << "," << row;
      low = std::min(low, a.values(col, row));
      high = std::max(high, a.values(col, row));
    }
  }
  EXPECT_LT(low, 0.9f * high);  // the box takes sky from the ground beside it
}

// The box hides part of the sky from the ground beside it and its shadow falls there: in colour,
// the shadow is darker than the open ground, both lighter than black; diffuse_now next to the box
// is below the open plane's.
TEST(RenderNowCli, ColourViewShowsTheBoxsShadowAndLessSkyBesideIt) {
  const std::string dir = temp_dir("render-now");
  const std::string obj = write_scene(dir, true), out = dir + "/box.tif", png = dir + "/box.png";
  const RunResult r =
      run_skyview("render " + obj + " " + out + kView + kSun + " --zenith-res 1 --colour-out " + png, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  CameraSpec spec;
  spec.position = {0, 0, 300};
  spec.up = {0, 1, 0};
  spec.width = spec.height = 320;
  spec.orthographic_width = 160;
  const Camera camera(spec, {0, 0, 0});
  auto at = [&](double x, double y, int& col, int& row) {
    double c = 0, rr = 0, d = 0;
    camera.project({x, y, 0}, c, rr, d);
    col = int(std::floor(c)), row = int(std::floor(rr));
  };
  const SunPosition sun = munich_sun();
  const double az = sun.azimuth_deg * kDegree;
  const double dx = -std::sin(az), dy = -std::cos(az);  // anti-solar on the ground
  int sc, sr, oc, orow, fc, fr;
  at(12 * dx, 12 * dy, sc, sr);      // in the shadow, close to the box
  at(-12 * dx, -12 * dy, oc, orow);  // sunlit, close to the box on its sunny side
  at(70, -70, fc, fr);               // open ground far away
  const RasterBand sunlit = read_band(out, 4), diffuse = read_band(out, 6);
  ASSERT_LT(sunlit.values(sc, sr), 0.5f);
  ASSERT_GE(sunlit.values(oc, orow), 0.5f);
  const Rgb shade = pixel(png, sc, sr), lit = pixel(png, oc, orow), open = pixel(png, fc, fr);
  EXPECT_GT(shade.sum(), 30);
  EXPECT_LT(shade.sum() + 100, lit.sum());
  EXPECT_EQ(shade.r, shade.g);  // grey surfaces
  EXPECT_LT(diffuse.values(sc, sr), 0.95f * diffuse.values(fc, fr));
  EXPECT_LT(std::abs(lit.sum() - open.sum()), 30);
}

// Looking straight up at an empty sky: the centre pixel is the zenith's colour under the fixed
// tone (reference_tone()); looking at the sun, the sun's pixel is the brightest of the picture.
TEST(RenderNowCli, EmptySkyShowsTheZenithColourAndTheSunIsTheBrightestPixel) {
  const std::string dir = temp_dir("render-now");
  const std::string obj = write_scene(dir, false), out = dir + "/up.tif", png = dir + "/up.png";
  RunResult r = run_skyview("render " + obj + " " + out +
                                " --camera 0,0,10 --look-at 0,0,100 --up 0,1,0 --size 101x101 --fov 40 --zenith-res 4 "
                                "--colour-out " +
                                png + kSun,
                            dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const SunPosition sun = munich_sun();
  const SkyColour sky(3.0, sun.zenith_deg * kDegree, sun.azimuth_deg * kDegree, reference_tone());
  const Srgb8 zenith = sky.display(0.0, 0.0);
  const Rgb centre = pixel(png, 50, 50);
  EXPECT_EQ(centre.r, zenith.r);
  EXPECT_EQ(centre.g, zenith.g);
  EXPECT_EQ(centre.b, zenith.b);
  EXPECT_GT(centre.b, centre.g);  // a clear zenith is blue
  EXPECT_GT(centre.g, centre.r);
  // The fixed tone: the zenith of this low morning sun is darker than the reference's key 0.5
  // (sRGB 188 for a grey), as a noon sky would be brighter.
  EXPECT_LT(0.2126 * centre.r + 0.7152 * centre.g + 0.0722 * centre.b, 188);

  // Towards the sun from 2 m above the ground.
  const double el = sun.elevation_deg * kDegree, az = sun.azimuth_deg * kDegree;
  const std::string look = std::to_string(100 * std::cos(el) * std::sin(az)) + "," +
                           std::to_string(100 * std::cos(el) * std::cos(az)) + "," +
                           std::to_string(2 + 100 * std::sin(el));
  const std::string png2 = dir + "/sun.png";
  r = run_skyview("render " + obj + " " + dir + "/sun.tif --camera 0,0,2 --look-at " + look +
                      " --size 101x101 --fov 40 --zenith-res 4 --colour-out " + png2 + kSun,
                  dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Rgb disc = pixel(png2, 50, 50);
  EXPECT_EQ(disc.sum(), 3 * 255);
  const RasterBand red = read_band(png2, 1), green = read_band(png2, 2), blue = read_band(png2, 3);
  int brightest_elsewhere = 0;
  for (int row = 0; row < 101; ++row) {
    for (int col = 0; col < 101; ++col) {
      if (std::hypot(col - 50, row - 50) < 5) continue;
      brightest_elsewhere =
          std::max(brightest_elsewhere, int(red.values(col, row) + green.values(col, row) + blue.values(col, row)));
    }
  }
  EXPECT_LT(brightest_elsewhere, disc.sum());
}

// --shadows hsm: the exact rays are traced too and the error shares in the metadata are those of
// shadow_error on the same receivers; --shadow-diff paints the leaks red and the acne blue.
TEST(RenderNowCli, HybridShadowMapErrorInMetadataMatchesADirectComputation) {
  const std::string dir = temp_dir("render-now");
  const std::string obj = write_scene(dir, true), out = dir + "/hsm.tif", diff = dir + "/diff.png";
  const RunResult r = run_skyview(
      "render " + obj + " " + out + kView + kSun + " --zenith-res 2 --shadows hsm --shadow-diff " + diff, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_FALSE(metadata(out, "SHADOW_EXACT_SECONDS").empty());

  const Scene scene = load_scene({obj});
  const RayScene rays(scene);
  CameraSpec spec;
  spec.position = {0, 0, 300};
  spec.up = {0, 1, 0};
  spec.width = spec.height = 320;
  spec.orthographic_width = 160;
  const Camera camera(spec, scene.origin);
  const ViewBuffers view = render_view_buffers(rays, camera);
  ShadowReceivers receivers;
  for (std::size_t i = 0; i < view.position.size(); ++i) {
    if (!view.hit(i)) continue;
    receivers.points.push_back(view.position[i]);
    receivers.normals.push_back(view.normal[i]);
  }
  const SunPosition sun = munich_sun();
  const Vec3f s = sun_direction_of(sun.azimuth_deg * kDegree, sun.elevation_deg * kDegree);
  ShadowOptions o;
  o.eye = Vec3f{float(camera.eye()[0]), float(camera.eye()[1]), float(camera.eye()[2])};
  const ShadowResult exact = sun_visibility(rays, scene, s, receivers, ShadowMethod::exact, o);
  const ShadowResult hsm = sun_visibility(rays, scene, s, receivers, ShadowMethod::hsm, o);
  const ShadowError e = shadow_error(rays, s, receivers, exact, hsm, o);
  ASSERT_EQ(std::to_string(e.receivers), metadata(out, "SHADOW_ERROR_RECEIVERS"));
  ASSERT_GT(e.edge_receivers, 0u);
  auto pct = [&](const char* key) { return std::stod(metadata(out, key)); };
  EXPECT_NEAR(pct("SHADOW_ERROR_WRONG_PCT"), 100 * e.wrong_share(), 1e-4);
  EXPECT_NEAR(pct("SHADOW_ERROR_EDGES_PCT"), 100 * e.share(e.wrong_edge), 1e-4);
  EXPECT_NEAR(pct("SHADOW_ERROR_INTERIORS_PCT"), 100 * e.share(e.wrong_interior), 1e-4);
  EXPECT_NEAR(pct("SHADOW_ERROR_LEAKS_PCT"), 100 * e.share(e.leaks), 1e-4);
  EXPECT_NEAR(pct("SHADOW_ERROR_ACNE_PCT"), 100 * e.share(e.acne), 1e-4);
  EXPECT_NEAR(pct("SHADOW_ERROR_EDGE_RECEIVERS_PCT"), 100 * e.share(e.edge_receivers), 1e-4);
  EXPECT_LT(pct("SHADOW_ERROR_WRONG_PCT"), 1.0);  // the hybrid maps agree almost everywhere here

  // The picture: one red pixel per leak, one blue per acne, white sky (none in this view).
  const RasterBand red = read_band(diff, 1), green = read_band(diff, 2), blue = read_band(diff, 3);
  std::size_t leaks = 0, acne = 0, grey = 0;
  for (int row = 0; row < 320; ++row) {
    for (int col = 0; col < 320; ++col) {
      const int rr = int(red.values(col, row)), g = int(green.values(col, row)), b = int(blue.values(col, row));
      leaks += rr == 230 && g == 30 && b == 30;
      acne += rr == 30 && g == 80 && b == 240;
      grey += rr == g && g == b && (rr == 200 || rr == 110);
    }
  }
  EXPECT_EQ(leaks, e.leaks);
  EXPECT_EQ(acne, e.acne);
  EXPECT_EQ(grey + leaks + acne, e.receivers);
}

TEST(RenderNowCli, CarelessCommandLines) {
  const std::string dir = temp_dir("render-now");
  const std::string obj = write_scene(dir, true), out = " " + dir + "/out.tif";
  const std::string small = " --camera 0,0,300 --look-at 0,0,0 --up 0,1,0 --orthographic 160 --size 40x40";
  expect_one_line_error(run_skyview("render " + obj + out + small + " --colour-out " + dir + "/c.png", dir),
                        "--colour-out applies only to", 2);
  expect_one_line_error(run_skyview("render " + obj + out + small + kSun + " --shadow-diff " + dir + "/d.png", dir),
                        "--shadow-diff applies only to", 2);
  expect_one_line_error(run_skyview("render " + obj + out + small + kSun + " --colour-out " + dir + "/c.tif", dir),
                        "--colour-out", 2);
}
