// The unit of a raster's heights: read from the band or the vertical CRS, assumed to be the metre
// only where the CRS is in metres or degrees, refused otherwise (height_unit.h).
#include "skyview/raster/height_unit.h"

#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <string>
#include <vector>

#include "cli_run.h"
#include "skyview/core/error.h"
#include "skyview/raster/raster_io.h"
#include "temp_dir.h"
#include "test_support.h"

namespace skyview {
namespace {

constexpr double kUsFoot = 1200.0 / 3937.0;

// A 4 x 3 raster of heights 10, 11, ... 21 in `crs`, 3 units a cell, its band's unit `unit`.
std::string write_heights(const std::string& dir, const std::string& name, const char* crs, double x0, double y0,
                          const std::string& unit) {
  GeoReference g;
  g.has_geotransform = true;
  g.geotransform = {x0, 3, 0, y0, 0, -3};
  g.crs_wkt = test::wkt_of(crs);
  std::vector<float> z(12);
  for (int i = 0; i < 12; ++i) z[static_cast<std::size_t>(i)] = 10.0f + static_cast<float>(i);
  const std::string path = dir + "/" + name;
  write_bands(path, 4, 3, g, {{"height", unit, z.data(), {}}}, {});
  return path;
}

// Height of cell i (row-major) as read, in metres.
double height(const Terrain& t, int i) { return t.base_height + t.heights(i % 4, i / 4); }

TEST(HeightUnit, NamesThatGdalAndGisFilesGiveHeights) {
  EXPECT_EQ(metres_per_height_unit("m"), 1.0);
  EXPECT_EQ(metres_per_height_unit(" Metre "), 1.0);
  EXPECT_EQ(metres_per_height_unit("meters"), 1.0);
  EXPECT_EQ(metres_per_height_unit("cm"), 0.01);
  EXPECT_EQ(metres_per_height_unit("ft"), 0.3048);
  EXPECT_EQ(metres_per_height_unit("Foot"), 0.3048);
  EXPECT_EQ(metres_per_height_unit("US survey foot"), kUsFoot);
  EXPECT_EQ(metres_per_height_unit("ftUS"), kUsFoot);
  EXPECT_EQ(metres_per_height_unit("m asl"), 1.0);
  EXPECT_EQ(metres_per_height_unit("usft"), kUsFoot);
  EXPECT_EQ(metres_per_height_unit("km"), 1000.0);
  EXPECT_EQ(metres_per_height_unit("furlong"), 0.0);
  EXPECT_EQ(metres_per_height_unit("1"), 0.0);
  EXPECT_EQ(metres_per_height_unit(""), 0.0);
}

TEST(HeightUnit, ABandInFeetIsReadInMetres) {
  const std::string dir = test::temp_dir("height-unit");
  const std::string path = write_heights(dir, "feet.tif", "EPSG:32633", 500000, 5000000, "ft");
  ReadReport report;
  const Terrain t = read_terrain(path, {}, &report);
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(height(t, i), (10.0 + i) * 0.3048, 1e-5) << i;
  EXPECT_EQ(report.z_scale, 0.3048);
  EXPECT_EQ(report.height_unit, "band unit 'ft'");
  // --z-scale wins over what the file says.
  ReadOptions given;
  given.z_scale = 2.0;
  const Terrain doubled = read_terrain(path, given, &report);
  EXPECT_NEAR(height(doubled, 5), 30.0, 1e-5);
  EXPECT_EQ(report.height_unit, "--z-scale");
}

TEST(HeightUnit, UnstatedHeightsAreMetresWhereTheCrsIsInMetresOrDegrees) {
  const std::string dir = test::temp_dir("height-unit");
  ReadReport report;
  const Terrain utm = read_terrain(write_heights(dir, "utm.tif", "EPSG:32633", 500000, 5000000, ""), {}, &report);
  EXPECT_NEAR(height(utm, 11), 21.0, 1e-5);
  EXPECT_EQ(report.z_scale, 1.0);
  EXPECT_NE(report.height_unit.find("the CRS is in metres"), std::string::npos) << report.height_unit;
  const Terrain geographic = read_terrain(write_heights(dir, "wgs84.tif", "EPSG:4326", 15, 45, ""), {}, &report);
  EXPECT_NEAR(height(geographic, 11), 21.0, 1e-5);
  EXPECT_NE(report.height_unit.find("geographic"), std::string::npos) << report.height_unit;
}

TEST(HeightUnit, UnstatedHeightsUnderAFeetCrsAreRefusedUntilTheUserSays) {
  const std::string dir = test::temp_dir("height-unit");
  // NAD83 / New York Long Island, in US survey feet.
  const std::string path = write_heights(dir, "ny.tif", "EPSG:2263", 980000, 200000, "");
  try {
    read_terrain(path, {});
    ADD_FAILURE() << "read heights of an unstated unit under a feet CRS";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("US survey foot"), std::string::npos) << what;
    EXPECT_NE(what.find("--z-scale"), std::string::npos) << what;
  }
  ReadOptions feet;
  feet.z_scale = kUsFoot;
  EXPECT_NEAR(height(read_terrain(path, feet), 3), 13.0 * kUsFoot, 1e-5);
  // A unit nobody can convert is refused the same way.
  const std::string odd = write_heights(dir, "odd.tif", "EPSG:32633", 500000, 5000000, "furlong");
  EXPECT_THROW(read_terrain(odd, {}), Error);
}

TEST(HeightUnit, GeoTiffsWithACompoundCrsGiveTheirVerticalUnit) {
  const std::string dir = test::temp_dir("height-unit");
  ReadReport report;
  // UTM 33N in metres over NAVD88 heights in US survey feet: GDAL hands the vertical unit to the band.
  const Terrain utm_ft =
      read_terrain(write_heights(dir, "utm_ft.tif", "EPSG:32633+6360", 500000, 5000000, ""), {}, &report);
  EXPECT_NEAR(height(utm_ft, 2), 12.0 * kUsFoot, 1e-5);
  EXPECT_NEAR(report.z_scale, kUsFoot, 1e-12);
  // New York Long Island in US survey feet over NAVD88 heights in metres: not refused.
  const Terrain ny_m = read_terrain(write_heights(dir, "ny_m.tif", "EPSG:2263+5703", 980000, 200000, ""), {}, &report);
  EXPECT_NEAR(height(ny_m, 2), 12.0, 1e-5);
  EXPECT_EQ(report.z_scale, 1.0);
  // A band unit it does not know gives way to a vertical CRS; "unknown" is no unit at all.
  const Terrain odd =
      read_terrain(write_heights(dir, "odd_ft.tif", "EPSG:32633+6360", 500000, 5000000, "elevation"), {}, &report);
  EXPECT_NEAR(report.z_scale, kUsFoot, 1e-12) << report.height_unit;
  const Terrain unknown =
      read_terrain(write_heights(dir, "unknown.tif", "EPSG:32633", 500000, 5000000, "unknown"), {}, &report);
  EXPECT_EQ(report.z_scale, 1.0) << report.height_unit;
}

TEST(HeightUnit, ACompoundCrsGivesItsVerticalUnit) {
  init_gdal();
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDatasetUniquePtr ds(mem->Create("", 2, 2, 1, GDT_Float32, nullptr));
  OGRSpatialReference metres_over_feet;  // ETRS89 / UTM 32N + NAVD88 height (ftUS)
  ASSERT_EQ(metres_over_feet.SetFromUserInput("EPSG:25832+6360"), OGRERR_NONE);
  const HeightUnit u = height_unit(*ds->GetRasterBand(1), &metres_over_feet, 0.0, "mem");
  EXPECT_NEAR(u.metres, kUsFoot, 1e-15);
  EXPECT_NE(u.source.find("vertical CRS"), std::string::npos) << u.source;
  OGRSpatialReference plain;
  ASSERT_EQ(plain.SetFromUserInput("EPSG:25832"), OGRERR_NONE);
  EXPECT_EQ(height_unit(*ds->GetRasterBand(1), &plain, 0.0, "mem").metres, 1.0);
  EXPECT_EQ(height_unit(*ds->GetRasterBand(1), nullptr, 0.0, "mem").metres, 1.0);
}

TEST(HeightUnit, ACloudsHeightsShareItsCoordinatesUnit) {
  OGRSpatialReference feet, metres_over_feet, output_feet;
  ASSERT_EQ(feet.SetFromUserInput("EPSG:2994"), OGRERR_NONE);  // Oregon GIC Lambert (ft)
  ASSERT_EQ(metres_over_feet.SetFromUserInput("EPSG:32633+6360"), OGRERR_NONE);
  ASSERT_EQ(output_feet.SetFromUserInput("EPSG:2263"), OGRERR_NONE);
  EXPECT_EQ(cloud_height_unit(&feet, nullptr, 0.0, 0.0).metres, 0.3048);
  // The file's own vertical unit beats the horizontal unit, a compound CRS beats both.
  EXPECT_EQ(cloud_height_unit(&feet, nullptr, 1.0, 0.0).metres, 1.0);
  EXPECT_NEAR(cloud_height_unit(&metres_over_feet, nullptr, 1.0, 0.0).metres, kUsFoot, 1e-12);
  // No CRS of its own: the output's, and said so.
  const HeightUnit borrowed = cloud_height_unit(nullptr, &output_feet, 0.0, 0.0);
  EXPECT_NEAR(borrowed.metres, kUsFoot, 1e-12);
  EXPECT_NE(borrowed.source.find("output CRS"), std::string::npos) << borrowed.source;
  EXPECT_EQ(cloud_height_unit(nullptr, nullptr, 0.0, 0.0).metres, 1.0);
  EXPECT_EQ(cloud_height_unit(&feet, nullptr, 0.0, 2.0).metres, 2.0);
}

TEST(HeightUnit, TheCommandLineRecordsTheUnitOrSaysWhatToGive) {
  const std::string dir = test::temp_dir("height-unit");
  const std::string ny = write_heights(dir, "ny.tif", "EPSG:2263", 980000, 200000, "");
  test::expect_one_line_error(test::run_skyview("svf " + ny + " " + dir + "/a.tif", dir), "give --z-scale");
  const test::RunResult r = test::run_skyview("svf " + ny + " " + dir + "/b.tif --z-scale 0.3048006096", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string feet = write_heights(dir, "feet.tif", "EPSG:32633", 500000, 5000000, "US survey foot");
  ASSERT_EQ(test::run_skyview("svf " + feet + " " + dir + "/c.tif", dir).exit_code, 0);
  init_gdal();
  GDALDatasetUniquePtr given(GDALDataset::Open((dir + "/b.tif").c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(given);
  EXPECT_STREQ(given->GetMetadataItem("Z_SCALE"), "0.3048006096");
  EXPECT_STREQ(given->GetMetadataItem("HEIGHT_UNIT"), "--z-scale");
  GDALDatasetUniquePtr stated(GDALDataset::Open((dir + "/c.tif").c_str(), GDAL_OF_RASTER));
  ASSERT_TRUE(stated);
  EXPECT_STREQ(stated->GetMetadataItem("HEIGHT_UNIT"), "band unit 'US survey foot'");
}

}  // namespace
}  // namespace skyview
