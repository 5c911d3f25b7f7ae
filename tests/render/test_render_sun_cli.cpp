// `skyview render --time`: sun shadows and the beam on a camera view. A box on a plane seen from
// straight above: its shadow ends H / tan(elevation) beyond the box along the anti-solar azimuth,
// the hybrid shadow maps agree with the exact rays, and careless command lines fail in one line.
#include <gdal_priv.h>

#include <cmath>
#include <numbers>
#include <string>

#include "core/cli_run.h"
#include "render_test_support.h"
#include "skyview/raster/raster_read.h"
#include "skyview/render/camera.h"
#include "skyview/solar/solar_position.h"
#include "skyview/solar/time_parse.h"
#include "temp_dir.h"

using namespace skyview;
using namespace skyview::test;

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr float kBoxHeight = 20.0f, kBoxHalf = 5.0f;
// Munich, an equinox morning: the sun at about 115° azimuth, 26° elevation.
const char* kSun = " --time 2024-03-20T08:00Z --lat 48 --lon 11 --elevation 0";
const char* kTime = "2024-03-20T08:00Z";
// Straight down, 0.5 m pixels, north up.
const char* kView = " --camera 0,0,300 --look-at 0,0,0 --up 0,1,0 --orthographic 160 --size 320x320";

std::string box_obj(const std::string& dir) {
  Scene s;
  s.meshes.push_back(ground_mesh(200));
  s.meshes.push_back(box_mesh("box", {-kBoxHalf, -kBoxHalf, 0}, {kBoxHalf, kBoxHalf, kBoxHeight}));
  const std::string path = dir + "/box.obj";
  write_obj(s, path);
  return path;
}

Camera view_camera() {
  CameraSpec spec;
  spec.position = {0, 0, 300};
  spec.look_at = {0, 0, 0};
  spec.up = {0, 1, 0};
  spec.width = spec.height = 320;
  spec.orthographic_width = 160;
  return Camera(spec, {0, 0, 0});
}

std::string metadata(const std::string& path, const char* key) {
  init_gdal();
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER));
  const char* v = ds ? ds->GetMetadataItem(key) : nullptr;
  return v ? v : "";
}

// The band's value at ground point (x, y).
float at_ground(const Camera& camera, const RasterBand& band, double x, double y) {
  double col = 0, row = 0, depth = 0;
  camera.project({x, y, 0}, col, row, depth);
  return band.values(static_cast<int>(std::floor(col)), static_cast<int>(std::floor(row)));
}

}  // namespace

TEST(RenderSunCli, BoxShadowEndsAtHOverTanElevationAlongTheAntiSolarAzimuth) {
  const std::string dir = temp_dir("render-sun");
  const std::string obj = box_obj(dir), out = dir + "/exact.tif";
  const RunResult r = run_skyview("render " + obj + " " + out + kView + kSun + " --zenith-res 1", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RasterBand sunlit = read_band(out, 4), direct = read_band(out, 5);
  EXPECT_EQ(sunlit.description, "sunlit");
  EXPECT_EQ(direct.description, "direct_now");
  EXPECT_EQ(direct.unit, "W m-2");
  EXPECT_EQ(read_band(out, 8).description, "depth");
  EXPECT_EQ(metadata(out, "SHADOW_METHOD"), "exact");

  const SunPosition sun = solar_position(parse_time(kTime).unix_utc, Site{48.0, 11.0, 0.0});
  ASSERT_GT(sun.elevation_deg, 15.0);
  EXPECT_NEAR(std::stod(metadata(out, "SUN_ELEVATION_DEG")), sun.elevation_deg, 1e-6);
  EXPECT_NEAR(std::stod(metadata(out, "SUN_AZIMUTH_DEG")), sun.azimuth_deg, 1e-6);
  const double az = sun.azimuth_deg * kDegree, el = sun.elevation_deg * kDegree;
  const double dx = -std::sin(az), dy = -std::cos(az);  // anti-solar, on the ground
  // From the box's centre its wall lies b along (dx, dy); the shadow ends H / tan(el) beyond it.
  const double b = kBoxHalf / std::max(std::abs(dx), std::abs(dy));
  const double expected = b + kBoxHeight / std::tan(el);
  double end = -1;
  bool shaded = false;
  for (double t = b + 0.25; t < 78; t += 0.05) {
    const float v = at_ground(view_camera(), sunlit, t * dx, t * dy);
    if (v < 0.5f) shaded = true;
    if (shaded && v >= 0.5f) {
      end = t;
      break;
    }
  }
  ASSERT_TRUE(shaded);
  const double footprint = 160.0 / 320.0;
  EXPECT_NEAR(end, expected, 2 * footprint) << "expected " << expected << " m from the box's centre";
  // Sunlit ground gets DNI · sin(el), shaded ground nothing, the sky pixels nothing at all.
  const double dni = std::stod(metadata(out, "DIRECT_NORMAL_W_M2"));
  EXPECT_GT(dni, 300.0);
  EXPECT_LT(dni, 1100.0);
  EXPECT_NEAR(at_ground(view_camera(), direct, -60 * dx, -60 * dy), dni * std::sin(el), 0.002 * dni);
  EXPECT_EQ(at_ground(view_camera(), direct, (b + 5) * dx, (b + 5) * dy), 0.0f);
  // The roof faces the sun at its zenith angle: the same beam times sin(el).
  EXPECT_NEAR(at_ground(view_camera(), direct, 0, 0), dni * std::sin(el), 0.002 * dni);
}

TEST(RenderSunCli, HybridShadowMapsAgreeWithTheExactRays) {
  const std::string dir = temp_dir("render-sun");
  const std::string obj = box_obj(dir), exact = dir + "/exact.tif", hsm = dir + "/hsm.tif";
  RunResult r = run_skyview("render " + obj + " " + exact + kView + kSun + " --zenith-res 2", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_skyview("render " + obj + " " + hsm + kView + kSun + " --zenith-res 2 --shadows hsm", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(metadata(hsm, "SHADOW_METHOD"), "hsm");
  EXPECT_EQ(metadata(hsm, "SHADOW_CASCADES"), "3");
  EXPECT_EQ(metadata(hsm, "SHADOW_LAYERS"), "7");
  EXPECT_FALSE(metadata(hsm, "SHADOW_MAP_SECONDS").empty());
  const auto a = read_band(exact, 4).values.values(), b = read_band(hsm, 4).values.values();
  ASSERT_EQ(a.size(), b.size());
  std::size_t hits = 0, same = 0, shade = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(std::isnan(a[i]), std::isnan(b[i])) << "pixel " << i;
    if (std::isnan(a[i])) continue;
    ++hits;
    same += (a[i] >= 0.5f) == (b[i] >= 0.5f);
    shade += a[i] < 0.5f;
  }
  ASSERT_GT(hits, 100000u);
  EXPECT_GT(shade, 2000u);  // the box's shadow is in view
  EXPECT_GE(static_cast<double>(same) / hits, 0.99) << same << " of " << hits;
}

TEST(RenderSunCli, SoftSunAndCarelessCommandLines) {
  const std::string dir = temp_dir("render-sun");
  const std::string obj = box_obj(dir), out = " " + dir + "/out.tif";
  const std::string small = " --camera 0,0,300 --look-at 0,0,0 --up 0,1,0 --orthographic 160 --size 40x40";
  const RunResult soft = run_skyview("render " + obj + out + small + kSun + " --soft --zenith-res 4", dir);
  ASSERT_EQ(soft.exit_code, 0) << soft.err;
  EXPECT_EQ(read_band(dir + "/out.tif", 4).description, "sun_fraction");
  // Night in Munich.
  expect_one_line_error(
      run_skyview("render " + obj + out + small + " --overwrite --time 2024-03-20T22:00Z --lat 48 --lon 11", dir),
      "degrees below the horizon", 1);
  expect_one_line_error(
      run_skyview("render " + obj + out + small + kSun + " --overwrite --shadows hsm --cascades 0", dir), "--cascades",
      2);
  expect_one_line_error(
      run_skyview("render " + obj + out + small + kSun + " --overwrite --shadows lvsm --layers 0", dir), "--layers", 2);
  expect_one_line_error(
      run_skyview("render " + obj + out + small + kSun + " --overwrite --shadows pcf --shadow-map-size 2", dir),
      "--shadow-map-size", 2);
  expect_one_line_error(run_skyview("render " + obj + out + small + kSun + " --overwrite --cascades 2", dir),
                        "--cascades applies only to", 2);
  expect_one_line_error(run_skyview("render " + obj + out + small + kSun + " --overwrite --shadows pcf --soft", dir),
                        "--soft applies only to", 2);
  expect_one_line_error(run_skyview("render " + obj + out + small + " --overwrite --shadows hsm", dir),
                        "--shadows applies only to", 2);
  // An OBJ has no CRS: the sun needs a site.
  expect_one_line_error(run_skyview("render " + obj + out + small + " --overwrite --time 2024-03-20T08:00Z", dir),
                        "no CRS to place the sun", 1);
}

// A UTM scene: the site is its centre, and the sun's true azimuth is turned onto the grid by the
// meridian convergence, grid = true − (λ − λ0)·sin φ (zone 32: λ0 = 9° E).
TEST(RenderSunCli, UtmSceneTakesItsSiteAndGridNorthFromItsCrs) {
  const std::string dir = temp_dir("render-sun");
  Scene s;
  s.meshes.push_back(ground_mesh(100));
  s.meshes.push_back(box_mesh("box", {-kBoxHalf, -kBoxHalf, 0}, {kBoxHalf, kBoxHalf, kBoxHeight}));
  for (SceneMesh& m : s.meshes) {
    for (Vec3f& v : m.vertices) v[0] += 400000.0f, v[1] += 5335000.0f;
  }
  write_obj(s, dir + "/utm.obj");
  const std::string out = dir + "/utm.tif";
  const RunResult r = run_skyview("render " + dir + "/utm.obj " + out +
                                      " --s_srs EPSG:25832 --camera 400000,5335000,300 --look-at 400000,5335000,0 "
                                      "--up 0,1,0 --orthographic 160 --size 32x32 --zenith-res 4 --time " +
                                      kTime,
                                  dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const double lat = std::stod(metadata(out, "LATITUDE")), lon = std::stod(metadata(out, "LONGITUDE"));
  EXPECT_NEAR(lat, 48.16, 0.01);
  EXPECT_NEAR(lon, 7.655, 0.01);
  EXPECT_EQ(metadata(out, "SITE_SOURCE"), "the scene's centre");
  const double az = std::stod(metadata(out, "SUN_AZIMUTH_DEG")),
               grid = std::stod(metadata(out, "SUN_GRID_AZIMUTH_DEG"));
  EXPECT_NEAR(grid - az, -(lon - 9.0) * std::sin(lat * kDegree), 0.02);
  EXPECT_NEAR(az, solar_position(parse_time(kTime).unix_utc, Site{lat, lon, 0.0}).azimuth_deg, 0.01);
}
