// Shadows and sun hours: a tower's shadow is H / tan(elevation) long along the sun's azimuth, an
// open plane's sun hours are its day length, and bad input gives one error line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/cli_run.h"
#include "core/test_support.h"
#include "exposure_test_support.h"
#include "skyview/core/error.h"
#include "skyview/exposure/shadow.h"
#include "skyview/exposure/sun_hours.h"
#include "skyview/solar/sun_events.h"
#include "skyview/solar/time_parse.h"

namespace skyview {
namespace {

using test::kDegree;

TEST(Shadow, TowerShadowIsHeightOverTanElevationLong) {
  // A 9 x 9 m block 20 m high on a plane of 1 m cells: over cell centres its top edge lies 4 m
  // from the centre, so along the ray from the centre away from the sun the shadow ends at the
  // block's edge on that ray plus H / tan(elevation).
  const double height = 20.0, half = 4.0;
  const Terrain t = test::terrain_of(
      [&](double e, double n) { return std::abs(e) <= half + 0.1 && std::abs(n) <= half + 0.1 ? height : 0.0; }, 201,
      1.0);
  struct Case {
    double lat;
    const char* time;
  };
  for (const Case& c : {Case{45, "2024-06-21T07:00Z"}, Case{45, "2024-06-21T15:30Z"}, Case{60, "2024-03-20T10:00Z"},
                        Case{0, "2024-12-21T08:30Z"}, Case{-33, "2024-01-10T14:00Z"}}) {
    Site site;
    site.latitude_deg = c.lat;
    const SunPosition sun = solar_position(parse_time(c.time).unix_utc, site);
    SCOPED_TRACE(testing::Message() << "latitude " << c.lat << " at " << c.time << ": sun at " << sun.azimuth_deg
                                    << ", " << sun.elevation_deg);
    ASSERT_GT(sun.elevation_deg, 14.0);
    ShadowRequest r;
    r.sun_azimuth = sun.azimuth_deg * kDegree;
    r.sun_elevation = sun.elevation_deg * kDegree;
    const auto engine = make_horizon_engine("sweep", shadow_horizon_params(HorizonParams{}, r.sun_azimuth));
    ProgressCounter progress;
    const ShadowBands b = compute_shadow(*engine, t, Window::whole(t), r, progress);
    const double away = r.sun_azimuth + M_PI, se = std::sin(away), sn = std::cos(away);
    const double edge = half / std::max(std::abs(se), std::abs(sn));
    const double expected = edge + height / std::tan(r.sun_elevation);
    ASSERT_LT(expected, 95.0);
    double tip = 0.0;
    for (double d = 0.0; d < 98.0; d += 0.25) {
      const int col = 100 + static_cast<int>(std::lround(d * se)), row = 100 - static_cast<int>(std::lround(d * sn));
      if (b.sunlit(col, row) == 0.0f) tip = d;
    }
    EXPECT_NEAR(tip, expected, 1.0);
    // Ahead of the block, towards the sun, the plane is lit; on the block's top too.
    EXPECT_EQ(b.sunlit(100 + static_cast<int>(std::lround(-20 * se)), 100 + static_cast<int>(std::lround(20 * sn))),
              1.0f);
    EXPECT_EQ(b.sunlit(100, 100), 1.0f);
    EXPECT_NEAR(b.incidence_cos(100, 100), std::sin(r.sun_elevation), 1e-6);
  }
}

// A cell 3 m from the raster's east edge on flat ground, the sun at 135°, and a 20 m block whose
// east side is the raster's edge, starting one cell south of where the sun's ray leaves the raster
// (at the corner of the block's outer cell). Over the mesh of cell centres the ray leaves at the
// vertex (40, 23) and meets nothing: 0°, lit. The engines extend the raster by a ring of one cell
// (extend_at_raster_edges) that copies the block to column 41, half a cell beyond the raster's
// extent; until Dec 7 the ray ran on over that ring to (41, 24): atan(20 / 4√2) = 74.2°, in shadow,
// and 2 and 4 of the city's 1000 cells in tests/render/test_shadow_maps.cpp disagreed with exact
// rays (docs/shadows.md). Every engine's track now ends where it leaves the raster's extent (half a
// cell beyond the outer centres, track_box.h), after its last crossing at (40, 23). (The sampled
// engine turns each cell's direction set at random, so it cannot aim at the sun: not listed.)
TEST(Shadow, TheRingBeyondTheRasterEdgeCastsNoShadow) {
  // 41 x 41 cells of 1 m; cell (col, row) lies at east = col - 20, north = 20 - row.
  const int cell_col = 37, cell_row = 20;
  const Terrain t = test::terrain_of(
      [&](double e, double n) { return e >= 36 - 20 - 0.1 && n <= 20 - 24 + 0.1 && n >= 20 - 30 - 0.1 ? 20.0 : 0.0; },
      41, 1.0);
  ASSERT_EQ(t.heights(40, 24), 20.0f);
  ASSERT_EQ(t.heights(36, 30), 20.0f);
  ASSERT_EQ(t.heights(40, 23), 0.0f);
  ASSERT_EQ(t.heights(35, 24), 0.0f);
  for (const char* method : {"raycast", "sweep", "march"}) {
    SCOPED_TRACE(method);
    ShadowRequest r;
    r.sun_azimuth = 135 * kDegree;
    r.sun_elevation = 25 * kDegree;
    const auto engine = make_horizon_engine(method, shadow_horizon_params(HorizonParams{}, r.sun_azimuth));
    ProgressCounter progress;
    HorizonField field;
    engine->compute(t, Window{cell_col, cell_row, 1, 1}, field, progress);
    EXPECT_NEAR(field.upper[0], 0.0, 0.5 * kDegree);  // 74.2° until Dec 7
    const ShadowBands b = compute_shadow(*engine, t, Window::whole(t), r, progress);
    EXPECT_EQ(b.sunlit(cell_col, cell_row), 1.0f);
  }
}

TEST(Shadow, SoftShadowsCountTheDiscsVisibleShare) {
  const double r = kSunAngularRadius;
  EXPECT_DOUBLE_EQ(visible_disc_fraction(0.0, r), 0.5);
  EXPECT_DOUBLE_EQ(visible_disc_fraction(r, r), 1.0);
  EXPECT_DOUBLE_EQ(visible_disc_fraction(-r, r), 0.0);
  // Half the radius above: the segment below the chord at −r/2 is (π/3 − √3/4) / π of the disc.
  EXPECT_NEAR(visible_disc_fraction(0.5 * r, r), 1.0 - (M_PI / 3 - std::sqrt(3.0) / 4) / M_PI, 1e-12);
  EXPECT_NEAR(visible_disc_fraction(0.3 * r, r) + visible_disc_fraction(-0.3 * r, r), 1.0, 1e-12);
  // A wall whose top stands exactly at the sun's centre from a cell hides half the disc.
  const Terrain t = test::terrain_of([](double, double n) { return n > 10.5 ? 10.0 : 0.0; }, 61, 1.0);
  ShadowRequest req;
  req.sun_azimuth = 0.0;  // due north, over the wall
  req.sun_elevation = std::atan(10.0 / 11.0);
  req.soft = true;
  const auto engine = make_horizon_engine("sweep", shadow_horizon_params(HorizonParams{}, 0.0));
  ProgressCounter progress;
  const ShadowBands b = compute_shadow(*engine, t, Window::whole(t), req, progress);
  EXPECT_NEAR(b.sunlit(30, 30), 0.5, 1e-3);  // the cell 11 m south of the wall's top edge
  EXPECT_EQ(b.sunlit(30, 25), 0.0f);         // 6 m from it the top stands 59° high, far above the disc
  EXPECT_EQ(b.sunlit(30, 40), 1.0f);         // 21 m from it, 25°: far below
  EXPECT_EQ(b.sunlit(30, 10), 1.0f);         // on the wall
}

TEST(Shadow, TheSunMustBeUp) {
  const Terrain t = test::terrain_of([](double, double) { return 0.0; }, 9, 1.0);
  ShadowRequest r;
  r.sun_elevation = -0.1;
  const auto engine = make_horizon_engine("sweep", shadow_horizon_params(HorizonParams{}, 0.0));
  ProgressCounter progress;
  EXPECT_THROW(compute_shadow(*engine, t, Window::whole(t), r, progress), Error);
  r.sun_elevation = 0.5;
  r.sun_azimuth = 1.0;  // the engine is turned to 0
  EXPECT_THROW(compute_shadow(*engine, t, Window::whole(t), r, progress), Error);
}

TEST(SunHours, OpenPlaneSeesTheSunForTheDayLength) {
  const Terrain flat = test::terrain_of([](double, double) { return 0.0; }, 21, 5.0);
  struct Case {
    double lat;
    CivilDate date;
  };
  for (const Case& c : {Case{0, {2024, 3, 21}}, Case{45, {2024, 6, 21}}, Case{45, {2024, 12, 21}},
                        Case{60, {2024, 9, 1}}, Case{-35, {2024, 6, 21}}}) {
    SCOPED_TRACE(testing::Message() << "latitude " << c.lat << ", " << c.date.year << "-" << c.date.month << "-"
                                    << c.date.day);
    Site site;
    site.latitude_deg = c.lat;
    site.longitude_deg = 10.0;
    const double start = static_cast<double>(days_from_civil(c.date)) * 86400.0;
    const double step_h = 10.0 / 60;
    const std::vector<SunStep> steps = daylight_steps(site, start, start + 86400.0, step_h * 3600);
    HorizonParams p;
    p.directions = 32;
    const auto engine = make_horizon_engine("sweep", p);
    ProgressCounter progress;
    const SunHoursBands b = compute_sun_hours(*engine, flat, Window::whole(flat), steps, start, progress);
    const SunEvents events = sun_events(c.date, 0.0, site);
    // The events' day runs from the upper limb's rise with standard refraction, 0.83° lower than
    // the centre seen at 0°: a few minutes each side, within a step.
    EXPECT_NEAR(b.sun_hours(10, 10), events.day_length_h(), step_h);
    ASSERT_TRUE(events.sunrise_utc.has_value());
    EXPECT_NEAR(b.first_sun(10, 10), (*events.sunrise_utc - start) / 3600, step_h);
    EXPECT_NEAR(b.last_sun(10, 10), (*events.sunset_utc - start) / 3600, step_h);
  }
}

TEST(SunHours, APitTheSunNeverClearsHasNone) {
  // 60° N in mid-December the sun stays below 7°; the pit's rim stands 20° above its centre.
  const Terrain pit = test::terrain_of(circular_pit(30.0, 30.0 * std::tan(20 * kDegree)), 81, 1.0);
  Site site;
  site.latitude_deg = 60.0;
  const double start = parse_time("2024-12-15T00:00Z").unix_utc;
  const std::vector<SunStep> steps = daylight_steps(site, start, start + 86400.0, 600.0);
  HorizonParams p;
  p.directions = 32;
  const auto engine = make_horizon_engine("sweep", p);
  ProgressCounter progress;
  const SunHoursBands b = compute_sun_hours(*engine, pit, Window::whole(pit), steps, start, progress);
  EXPECT_EQ(b.sun_hours(40, 40), 0.0f);
  EXPECT_TRUE(std::isnan(b.first_sun(40, 40)));
  EXPECT_GT(b.sun_hours(2, 2), 4.0f);  // outside, a short day
}

// A small UTM DSM (57.7° N, 15° E) with and without its CRS.
std::string write_dsm(const std::string& dir, bool with_crs) {
  GeoReference g;
  g.geotransform = {500000.0, 2.0, 0.0, 6400000.0, 0.0, -2.0};
  g.has_geotransform = true;
  if (with_crs) g.crs_wkt = test::wkt_of("EPSG:32633");
  const Terrain t = rasterize([](double e, double n) { return std::hypot(e, n) < 6 ? 10.0 : 0.0; }, 31, 31, g);
  const std::string path = dir + (with_crs ? "/dsm.tif" : "/nocrs.tif");
  write_terrain(path, t, WriteOptions{});
  return path;
}

TEST(ShadowCli, WritesBandsAndRefusesBadInputInOneLine) {
  const std::string dir = test::temp_dir("shadow-cli");
  const std::string dsm = write_dsm(dir, true), nocrs = write_dsm(dir, false), out = " " + dir + "/x.tif";
  const test::RunResult ok = test::run_skyview("shadow " + dsm + out + " --time 2024-06-21T12:00+02:00 --soft", dir);
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const RasterBand fraction = read_band(dir + "/x.tif", 1);
  EXPECT_EQ(fraction.description, "sun_fraction");
  const test::RunResult hours = test::run_skyview("sunhours " + dsm + " " + dir +
                                                      "/h.tif --from 2024-03-21T00:00 --to 2024-03-22T00:00 "
                                                      "--tz Europe/Stockholm",
                                                  dir);
  ASSERT_EQ(hours.exit_code, 0) << hours.err;
  EXPECT_EQ(read_band(dir + "/h.tif", 3).description, "last_sun");
  std::filesystem::remove(dir + "/x.tif");
  struct Case {
    std::string args, message;
    int exit_code = 1;  // 2 for a bad command line
    int warnings = 0;   // lines said before the error (a raster without a CRS is warned about when read)
  };
  const Case cases[] = {
      {"shadow " + dsm + out + " --time 2024-06-21T23:30+02:00", "degrees below the horizon"},
      {"shadow " + dsm + out + " --time 2024-06-21T12:00+02:00 --directions 8", "--directions applies only to", 2},
      {"shadow " + nocrs + out + " --time 2024-06-21T12:00+02:00", "has no CRS to place the sun", 1, 1},
      {"shadow " + dsm + out + " --time -2100-06-21T12:00Z", "outside -2000..6000", 2},
      {"sunhours " + dsm + out + " --from 2024-12-21T10:00Z --to 2024-12-21T12:00Z --lat 80 --lon 15",
       "no daylight at 80, 15"},
      {"sunhours " + dsm + out + " --from 2024-12-21T10:00Z --to 2024-12-21T10:00Z", "the period is empty"},
      {"sunhours " + nocrs + out + " --from 2024-06-21T00:00Z --to 2024-06-22T00:00Z", "has no CRS to place the sun", 1,
       1},
      {"sunhours " + dsm + out + " --from 2024-06-21T00:00Z --to 2024-06-22T00:00Z --method sampled",
       "fixed, uniform directions"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    const test::RunResult r = test::run_skyview(c.args, dir);
    EXPECT_EQ(r.exit_code, c.exit_code) << r.err;
    EXPECT_NE(r.err.find("error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1 + c.warnings) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/x.tif"));
  }
}

}  // namespace
}  // namespace skyview
