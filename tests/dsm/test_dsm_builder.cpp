// skyview dsm: statistics of known points, footprints on a flat DEM, courtyards, grids across
// CRSs, and clear errors.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/test_support.h"
#include "skyview/dsm/dsm_builder.h"
#include "skyview/core/error.h"
#include "skyview/dsm/las_file.h"
#include "skyview/raster/raster_io.h"
#include "skyview/synthetic/synthetic.h"
#include "skyview/synthetic/synthetic_district.h"

#include <cpl_conv.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>
#include <unistd.h>

using namespace skyview;

namespace {

std::string dir_for(const std::string& name) { return skyview::test::temp_dir("dsm-" + name); }

using skyview::test::wkt_of;
constexpr auto wkt = wkt_of;

// A flat DEM at 100 m over [500000, 500100] x [6400000, 6400100] in UTM 33N, 1 m cells.
std::string flat_dem(const std::string& dir) {
  GeoReference g;
  g.has_geotransform = true;
  g.geotransform = {500000, 1, 0, 6400100, 0, -1};
  g.crs_wkt = wkt("EPSG:32633");
  Terrain t = rasterize([](double, double) { return 0.0; }, 100, 100, g, 100.0);
  write_terrain(dir + "/dem.tif", t, {});
  return dir + "/dem.tif";
}

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// A DEM and a footprint layer whose heights (field "h") stand above it.
DsmOptions footprints_on(const std::string& dem, const std::string& footprints) {
  DsmOptions d;
  d.dems = {dem};
  d.footprints = footprints;
  d.height_field = "h";
  return d;
}

// A GeoJSON layer in UTM 33N holding `features` (the text of its features array's items).
void write_utm_features(const std::string& path, const std::string& features) {
  write_text(path, R"({"type":"FeatureCollection",
    "crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32633"}},
    "features":[)" + features +
                       "]}");
}

TEST(DsmBuilder, KnownPointsGiveKnownCellValuesForEachStatistic) {
  const std::string dir = dir_for("stats");
  // Three returns in cell (2, 1) of a 1 m grid anchored at (0, 10), one in cell (0, 0).
  std::vector<LasPoint> pts = {{2.5, 8.5, 10.0, 0, 1, 1, 6},
                               {2.2, 8.7, 13.0, 0, 1, 1, 6},
                               {2.9, 8.1, 16.0, 0, 1, 1, 2},
                               {0.5, 9.5, 5.0, 0, 1, 1, 2}};
  LasWriteOptions o;
  o.crs_wkt = wkt("EPSG:32633");
  write_las(dir + "/p.las", pts, o);
  for (const auto& [stat, expected] :
       std::vector<std::pair<std::string, float>>{{"max", 16}, {"mean", 13}, {"min", 10}}) {
    DsmOptions d;
    d.points = {dir + "/p.las"};
    d.stat = stat;
    d.res = 1.0;
    d.te = std::array<double, 4>{0, 0, 10, 10};
    const DsmResult r = build_dsm(d);
    EXPECT_EQ(r.dsm.width(), 10);
    EXPECT_FLOAT_EQ(r.dsm(2, 1), expected) << stat;
    EXPECT_FLOAT_EQ(r.dsm(0, 0), 5.0f) << stat;
    EXPECT_TRUE(std::isnan(r.dsm(5, 5))) << stat;
  }
  DsmOptions ground;
  ground.points = {dir + "/p.las"};
  ground.ground_only = true;
  ground.te = std::array<double, 4>{0, 0, 10, 10};
  EXPECT_FLOAT_EQ(build_dsm(ground).dsm(2, 1), 16.0f);
  DsmOptions buildings = ground;
  buildings.ground_only = false;
  buildings.classes = {6};
  EXPECT_FLOAT_EQ(build_dsm(buildings).dsm(2, 1), 13.0f);
}

TEST(DsmBuilder, FootprintOnAFlatDemAndACourtyard) {
  const std::string dir = dir_for("footprints");
  const std::string dem = flat_dem(dir);
  // A 20 m square building of height 20, and a 40 m block with a 10 m courtyard of height 15.
  write_utm_features(dir + "/b.geojson", R"(
     {"type":"Feature","properties":{"h":20},"geometry":{"type":"Polygon","coordinates":[[[500010,6400010],[500030,6400010],[500030,6400030],[500010,6400030],[500010,6400010]]]}},
     {"type":"Feature","properties":{"h":15},"geometry":{"type":"Polygon","coordinates":[
        [[500050,6400050],[500090,6400050],[500090,6400090],[500050,6400090],[500050,6400050]],
        [[500065,6400065],[500075,6400065],[500075,6400075],[500065,6400075],[500065,6400065]]]}})");
  DsmOptions d = footprints_on(dem, dir + "/b.geojson");
  const DsmResult r = build_dsm(d);
  ASSERT_EQ(r.dsm.width(), 100);
  // Cell (c, r) has its centre at x = 500000 + c + 0.5, y = 6400100 - r - 0.5.
  EXPECT_FLOAT_EQ(r.dsm(20, 80), 120.0f);  // inside the square
  EXPECT_FLOAT_EQ(r.dsm(10, 89), 120.0f);  // first cell whose centre is inside
  EXPECT_FLOAT_EQ(r.dsm(9, 89), 100.0f);   // centre outside: terrain
  EXPECT_FLOAT_EQ(r.dsm(5, 5), 100.0f);
  EXPECT_FLOAT_EQ(r.dsm(55, 45), 115.0f);  // block
  EXPECT_FLOAT_EQ(r.dsm(70, 30), 100.0f);  // courtyard stays at terrain height
  EXPECT_FLOAT_EQ(r.dtm(20, 80), 100.0f);
  EXPECT_EQ(r.report.footprints_burned, 2);

  DsmOptions missing = d;
  missing.height_field = "height";
  EXPECT_THROW(build_dsm(missing), Error);
}

// A DEM whose cells sit half a metre off the whole metres (a LiDAR terrain's 563999.5) keeps its
// own lattice: its heights are copied, not resampled half a cell off with a nodata row and column
// added (until Dec 5 a 200² DEM became 201² of bilinear averages).
TEST(DsmBuilder, ADemKeepsItsOwnLattice) {
  const std::string dir = dir_for("lattice");
  GeoReference g;
  g.has_geotransform = true;
  g.geotransform = {500000.5, 1, 0, 6400100.5, 0, -1};
  g.crs_wkt = wkt("EPSG:32633");
  const Terrain t = rasterize([](double x, double y) { return 0.3 * x + 0.01 * x * y; }, 50, 40, g, 100.0);
  write_terrain(dir + "/half.tif", t, {});
  DsmOptions d;
  d.dems = {dir + "/half.tif"};
  const DsmResult r = build_dsm(d);
  ASSERT_EQ(r.dsm.width(), 50);
  ASSERT_EQ(r.dsm.height(), 40);
  EXPECT_EQ(r.georef.geotransform[0], 500000.5);
  EXPECT_EQ(r.georef.geotransform[3], 6400100.5);
  for (int row = 0; row < 40; ++row) {
    for (int col = 0; col < 50; ++col)
      ASSERT_NEAR(r.dsm(col, row), t.heights(col, row) + t.base_height, 1e-3) << col << ", " << row;
  }
}

// On sloping ground a building's height counts from the lowest ground under it, and its top is
// flat (until Dec 5 the roof copied the slope: terrain + height cell by cell).
TEST(DsmBuilder, ARoofOnASlopeIsFlatAboveTheLowestGround) {
  const std::string dir = dir_for("slope");
  GeoReference g;
  g.has_geotransform = true;
  g.geotransform = {500000, 1, 0, 6400100, 0, -1};
  g.crs_wkt = wkt("EPSG:32633");
  Terrain t = rasterize([](double x, double) { return 0.3 * x; }, 100, 100, g, 100.0);
  write_terrain(dir + "/slope.tif", t, {});
  write_utm_features(dir + "/b.geojson", R"(
     {"type":"Feature","properties":{"h":20},"geometry":{"type":"Polygon","coordinates":[[[500010,6400010],[500030,6400010],[500030,6400030],[500010,6400030],[500010,6400010]]]}})");
  DsmOptions d = footprints_on(dir + "/slope.tif", dir + "/b.geojson");
  const DsmResult r = build_dsm(d);
  // The footprint covers columns 10..29 and rows 70..89; the ground under it rises by 0.3 m a column.
  float lowest = std::numeric_limits<float>::infinity();
  for (int row = 70; row < 90; ++row) {
    for (int col = 10; col < 30; ++col) lowest = std::min(lowest, r.dtm(col, row));
  }
  EXPECT_GT(r.dtm(29, 80) - r.dtm(10, 80), 5.0f) << "the ground slopes under the building";
  for (int row = 70; row < 90; ++row) {
    for (int col = 10; col < 30; ++col) ASSERT_FLOAT_EQ(r.dsm(col, row), lowest + 20.0f) << col << ", " << row;
  }
  EXPECT_EQ(r.report.footprints_burned, 1);
}

// A packed DEM (Int16 centimetres: a scale of 0.01, and an offset) gives metres, as svf reads it;
// until Dec 5 the DSM held the stored integers, 10000 "m" for 100 m.
TEST(DsmBuilder, APackedDemIsUnpacked) {
  const std::string dir = dir_for("packed");
  const std::string path = dir + "/packed.tif";
  init_gdal();
  {
    GDALDatasetUniquePtr ds(
        GetGDALDriverManager()->GetDriverByName("GTiff")->Create(path.c_str(), 100, 100, 1, GDT_Int16, nullptr));
    double gt[6] = {500000, 1, 0, 6400100, 0, -1};
    ds->SetGeoTransform(gt);
    ds->SetProjection(wkt("EPSG:32633").c_str());
    GDALRasterBand* band = ds->GetRasterBand(1);
    band->SetScale(0.01);
    band->SetOffset(50.0);
    std::vector<std::int16_t> raw(100 * 100, 5000);  // 5000 * 0.01 + 50 = 100 m
    raw[50 * 100 + 50] = 6000;                       // 110 m
    ASSERT_EQ(band->RasterIO(GF_Write, 0, 0, 100, 100, raw.data(), 100, 100, GDT_Int16, 0, 0), CE_None);
  }
  DsmOptions d;
  d.dems = {path};
  const DsmResult r = build_dsm(d);
  ASSERT_EQ(r.dsm.width(), 100);
  EXPECT_FLOAT_EQ(r.dsm(10, 10), 100.0f);
  EXPECT_FLOAT_EQ(r.dsm(50, 50), 110.0f);
}

// A collection's polygons are a footprint; points, lines and features without a geometry are
// counted as left out (until Dec 5 they vanished uncounted, the collection's polygon with them).
TEST(DsmBuilder, FeaturesWithoutPolygonsAreCountedAndCollectionsBurned) {
  const std::string dir = dir_for("notpolygons");
  const std::string dem = flat_dem(dir);
  write_utm_features(dir + "/mixed.geojson", R"(
     {"type":"Feature","properties":{"h":20},"geometry":{"type":"Point","coordinates":[500050,6400050]}},
     {"type":"Feature","properties":{"h":20},"geometry":{"type":"LineString","coordinates":[[500050,6400050],[500060,6400060]]}},
     {"type":"Feature","properties":{"h":20},"geometry":null},
     {"type":"Feature","properties":{"h":20},"geometry":{"type":"GeometryCollection","geometries":[
        {"type":"Point","coordinates":[500000,6400000]},
        {"type":"Polygon","coordinates":[[[500010,6400010],[500030,6400010],[500030,6400030],[500010,6400030],[500010,6400010]]]}]}})");
  DsmOptions d = footprints_on(dem, dir + "/mixed.geojson");
  const DsmResult r = build_dsm(d);
  EXPECT_EQ(r.report.footprints_not_polygons, 3);
  EXPECT_EQ(r.report.footprints_burned, 1);
  EXPECT_FLOAT_EQ(r.dsm(20, 80), 120.0f);
}

// Footprints in a CRS turned far from the output's (New York's state plane, EPSG:2263, over a
// district in UTM 33N) widen the grid by no more than their own outlines: the layer's box
// transformed whole made a 100² DEM's grid 138 × 108 (until Dec 5).
TEST(DsmBuilder, FootprintsInATurnedCrsDoNotWidenTheGrid) {
  const std::string dir = dir_for("turned");
  const std::string dem = flat_dem(dir);
  OGRSpatialReference utm, ny;
  utm.importFromEPSG(32633);
  ny.importFromEPSG(2263);
  utm.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  ny.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> to_ny(OGRCreateCoordinateTransformation(&utm, &ny));
  ASSERT_TRUE(to_ny);
  const std::string path = dir + "/ny.gpkg";
  {
    GDALDatasetUniquePtr ds(
        GetGDALDriverManager()->GetDriverByName("GPKG")->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    OGRLayer* layer = ds->CreateLayer("b", &ny, wkbPolygon, nullptr);
    OGRFieldDefn h("h", OFTReal);
    layer->CreateField(&h);
    // Two buildings at opposite corners of the DEM, so the layer's box is the DEM's.
    for (const double at : {1.0, 89.0}) {
      OGRLinearRing ring;
      for (const auto& [dx, dy] : {std::pair{0.0, 0.0}, {10.0, 0.0}, {10.0, 10.0}, {0.0, 10.0}, {0.0, 0.0}})
        ring.addPoint(500000 + at + dx, 6400000 + at + dy);
      OGRPolygon polygon;
      polygon.addRing(&ring);
      ASSERT_EQ(polygon.transform(to_ny.get()), OGRERR_NONE);
      OGRFeature f(layer->GetLayerDefn());
      f.SetField("h", 60.0);  // feet
      f.SetGeometry(&polygon);
      ASSERT_EQ(layer->CreateFeature(&f), OGRERR_NONE);
    }
  }
  DsmOptions d = footprints_on(dem, path);
  d.footprint_z_scale = 0.3048;
  const DsmResult r = build_dsm(d);
  EXPECT_EQ(r.dsm.width(), 100);
  EXPECT_EQ(r.dsm.height(), 100);
  EXPECT_EQ(r.report.footprints_burned, 2);
}

// A building off the DEM has no terrain to stand on: it burns nothing and is counted as skipped
// (until Dec 3 it was counted as burned). With no DEM at all the error says what is missing.
TEST(DsmBuilder, AFootprintOffTheDemIsSkippedNotBurned) {
  const std::string dir = dir_for("offdem");
  const std::string dem = flat_dem(dir);
  write_utm_features(dir + "/b.geojson", R"(
     {"type":"Feature","properties":{"h":20},"geometry":{"type":"Polygon","coordinates":[[[500010,6400010],[500030,6400010],[500030,6400030],[500010,6400030],[500010,6400010]]]}},
     {"type":"Feature","properties":{"h":20},"geometry":{"type":"Polygon","coordinates":[[[500150,6400010],[500170,6400010],[500170,6400030],[500150,6400030],[500150,6400010]]]}})");
  DsmOptions d = footprints_on(dem, dir + "/b.geojson");
  const DsmResult r = build_dsm(d);
  EXPECT_EQ(r.report.footprints_burned, 1);
  EXPECT_EQ(r.report.footprints_skipped, 1);
  DsmOptions alone = d;
  alone.dems.clear();
  try {
    build_dsm(alone);
    ADD_FAILURE() << "no terrain: expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("footprint heights above the terrain need terrain under them"),
              std::string::npos)
        << e.what();
  }
  // The DEM's 1 m cells mean nothing in degrees: --res is asked for.
  DsmOptions degrees = d;
  degrees.t_srs = "EPSG:4326";
  try {
    build_dsm(degrees);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("give --res"), std::string::npos) << e.what();
  }
}

// Writers leave a LAS header's min and max stale: the grid comes from the points themselves (a
// header whose max x cut the cloud in half dropped half its returns without a word until Dec 3).
TEST(DsmBuilder, StaleLasHeaderBoundsDoNotCropTheCloud) {
  const std::string dir = dir_for("stale");
  std::vector<LasPoint> pts;
  for (int i = 0; i < 20; ++i) pts.push_back({500000.5 + i, 6400000.5 + i, 10.0 + i, 0, 1, 1, 2});
  LasWriteOptions o;
  o.crs_wkt = wkt("EPSG:32633");
  o.offset[0] = 500000, o.offset[1] = 6400000;
  write_las(dir + "/p.las", pts, o);
  {
    std::fstream f(dir + "/p.las", std::ios::in | std::ios::out | std::ios::binary);
    const double stale_max_x = 500005.0;
    f.seekp(179);  // max X in the public header block
    f.write(reinterpret_cast<const char*>(&stale_max_x), sizeof stale_max_x);
  }
  DsmOptions d;
  d.points = {dir + "/p.las"};
  d.res = 1.0;
  const DsmResult r = build_dsm(d);
  EXPECT_EQ(r.report.points_read, 20u);
  EXPECT_EQ(r.report.points_used, 20u);
  EXPECT_GE(r.dsm.width(), 20);
}

TEST(DsmBuilder, UtmAndDegreesDemsLandOnTheSameGrid) {
  const std::string dir = dir_for("crs");
  const std::string utm = flat_dem(dir);
  // The same area in EPSG:4326 with a gentle slope, warped onto the UTM grid by --t_srs/--te.
  const std::string geo = dir + "/geo.tif";
  {
    GeoReference g;
    g.has_geotransform = true;
    g.geotransform = {14.99, 0.00005, 0, 57.75, 0, -0.00005};
    g.crs_wkt = wkt("EPSG:4326");
    write_terrain(geo, rasterize([](double e, double) { return 50.0 + 0.01 * e; }, 800, 800, g), {});
  }
  DsmOptions a;
  a.dems = {utm};
  DsmOptions b;
  b.dems = {geo};
  b.t_srs = "EPSG:32633";
  b.te = std::array<double, 4>{500000, 6400000, 500100, 6400100};
  b.res = 1.0;
  const DsmResult ra = build_dsm(a), rb = build_dsm(b);
  EXPECT_EQ(ra.georef.geotransform, rb.georef.geotransform);
  EXPECT_EQ(ra.dsm.width(), rb.dsm.width());
  EXPECT_FALSE(std::isnan(rb.dsm(50, 50)));
}

TEST(DsmBuilder, BadInputGivesClearErrors) {
  const std::string dir = dir_for("errors");
  LasWriteOptions o;
  o.crs_wkt = wkt("EPSG:32633");
  write_las(dir + "/empty.las", {}, o);
  DsmOptions empty;
  empty.points = {dir + "/empty.las"};
  EXPECT_THROW(build_dsm(empty), Error);
  write_text(dir + "/pts.geojson", R"({"type":"FeatureCollection","features":[
     {"type":"Feature","properties":{"h":1},"geometry":{"type":"Point","coordinates":[1,2]}}]})");
  DsmOptions no_polygons;
  no_polygons.footprints = dir + "/pts.geojson";
  no_polygons.t_srs = "EPSG:32633";
  EXPECT_THROW(build_dsm(no_polygons), Error);
  DsmOptions nothing;
  EXPECT_THROW(build_dsm(nothing), Error);
  DsmOptions missing;
  missing.points = {dir + "/nope.las"};
  EXPECT_THROW(build_dsm(missing), Error);
  std::vector<LasPoint> pts = {{1, 1, 1, 0, 1, 1, 2}};
  write_las(dir + "/nocrs.las", pts, {});
  DsmOptions no_crs;
  no_crs.points = {dir + "/nocrs.las"};
  try {
    build_dsm(no_crs);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--t_srs"), std::string::npos);
  }
}

// The message of what build_dsm throws, or "" if it does not.
std::string error_of(const DsmOptions& d) {
  try {
    build_dsm(d);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// A grid of returns at whole metres: the grid snapped to them must hold the ones on its largest x
// and smallest y too (they lie on the far edges of half-open cells).
TEST(DsmBuilder, ReturnsOnTheGridsFarEdgesAreKept) {
  const std::string dir = dir_for("edges");
  std::vector<LasPoint> pts;
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 5; ++x) pts.push_back({500000.0 + x, 6400000.0 + y, 10.0 + x + 10 * y, 0, 1, 1, 2});
  }
  LasWriteOptions o;
  o.crs_wkt = wkt("EPSG:32633");
  o.offset[0] = 500000, o.offset[1] = 6400000;
  write_las(dir + "/grid.las", pts, o);
  DsmOptions d;
  d.points = {dir + "/grid.las"};
  d.res = 1.0;
  const DsmResult r = build_dsm(d);
  EXPECT_EQ(r.dsm.width(), 5);
  EXPECT_EQ(r.dsm.height(), 5);
  EXPECT_EQ(r.report.points_used, 25u);
  EXPECT_FLOAT_EQ(r.dsm(4, 4), 14.0f);  // x = 500004, y = 6400000: the far corner
}

// Footprint attributes that cannot be building heights, a footprint of no area, a grid that does
// not fit a geographic CRS and a DSM with no height anywhere are refused, not burned as zeros.
TEST(DsmBuilder, ImplausibleFootprintsAndGridsAreRefused) {
  const std::string dir = dir_for("implausible");
  const std::string dem = flat_dem(dir);
  auto footprints = [&](const std::string& name, const std::string& props, const std::string& ring) {
    write_utm_features(dir + "/" + name, R"({"type":"Feature","properties":)" + props +
                                             R"(,"geometry":{"type":"Polygon","coordinates":[[)" + ring + "]]}}");
    return dir + "/" + name;
  };
  const std::string square = "[500010,6400010],[500030,6400010],[500030,6400030],[500010,6400030],[500010,6400010]";
  DsmOptions d;
  d.dems = {dem};
  d.height_field = "h";
  d.footprints = footprints("text.geojson", R"({"h":"tall"})", square);
  EXPECT_NE(error_of(d).find("holds String, not numbers"), std::string::npos) << error_of(d);
  d.footprints = footprints("huge.geojson", R"({"h":1e9})", square);
  EXPECT_NE(error_of(d).find("outside -100 to 1000 m"), std::string::npos) << error_of(d);
  d.footprints =
      footprints("line.geojson", R"({"h":10})", "[500010,6400030],[500020,6400030],[500030,6400030],[500010,6400030]");
  const DsmResult flat = build_dsm(d);
  EXPECT_EQ(flat.report.footprints_skipped, 1);
  EXPECT_EQ(flat.report.footprints_burned, 0);
  EXPECT_FLOAT_EQ(flat.dsm(20, 70), 100.0f);

  DsmOptions no_height;
  no_height.footprints = footprints("bare.geojson", R"({"name":"x"})", square);
  EXPECT_NE(error_of(no_height).find("nothing gave the DSM a height"), std::string::npos) << error_of(no_height);

  LasWriteOptions o;
  o.offset[0] = 500000, o.offset[1] = 6400000;
  write_las(dir + "/utm.las", {{500000, 6400000, 1, 0, 1, 1, 2}, {500010, 6400010, 1, 0, 1, 1, 2}}, o);
  DsmOptions degrees;
  degrees.points = {dir + "/utm.las"};
  degrees.s_srs = "EPSG:4326";
  EXPECT_NE(error_of(degrees).find("give --res"), std::string::npos) << error_of(degrees);
  degrees.res = 1e-4;
  EXPECT_NE(error_of(degrees).find("not degrees"), std::string::npos) << error_of(degrees);
  DsmOptions reversed;
  reversed.dems = {dem};
  reversed.te = std::array<double, 4>{500100, 6400100, 500000, 6400000};
  EXPECT_NE(error_of(reversed).find("xmin < xmax"), std::string::npos) << error_of(reversed);
}

// A cloud's x, y and z are coordinates of one CRS: heights in feet are written in metres, from
// the CRS's own unit or its vertical part; --z-scale overrides; a DEM's band unit counts too.
TEST(DsmBuilder, HeightsInFeetAreWrittenInMetres) {
  const std::string dir = dir_for("feet");
  constexpr double kUsFoot = 1200.0 / 3937.0;
  // Oregon GIC Lambert in international feet (the Autzen samples' CRS).
  const std::vector<LasPoint> oregon = {{636000.5, 850000.5, 1000.0, 0, 1, 1, 2}};
  LasWriteOptions feet;
  feet.crs_wkt = wkt("EPSG:2994");
  write_las(dir + "/oregon.las", oregon, feet);
  DsmOptions d;
  d.points = {dir + "/oregon.las"};
  d.te = std::array<double, 4>{636000, 850000, 636002, 850002};
  DsmResult r = build_dsm(d);
  EXPECT_NEAR(r.dsm(0, 1), 304.8, 1e-3);
  ASSERT_EQ(r.report.height_units.size(), 1u);
  EXPECT_NE(r.report.height_units[0].find("foot"), std::string::npos) << r.report.height_units[0];
  d.points_z_scale = 1.0;
  EXPECT_NEAR(build_dsm(d).dsm(0, 1), 1000.0, 1e-3);
  d.points_z_scale = 0.0;
  d.z_scale = 1.0;  // for DEMs only
  EXPECT_NEAR(build_dsm(d).dsm(0, 1), 304.8, 1e-3);
  // Through the ground filter (an unclassified cloud), whose thresholds are metres.
  std::vector<LasPoint> flat;
  for (int i = 0; i < 9; ++i) flat.push_back({636000.5 + i % 3, 850000.5 + i / 3, 1000.0, 0, 1, 1, 1});
  write_las(dir + "/flat.las", flat, feet);
  DsmOptions filtered;
  filtered.points = {dir + "/flat.las"};
  filtered.ground_only = true;
  filtered.denoise = true;
  filtered.te = std::array<double, 4>{636000, 850000, 636003, 850003};
  const DsmResult ground = build_dsm(filtered);
  EXPECT_EQ(ground.report.ground_source, "morphological filter");
  EXPECT_NEAR(ground.dsm(1, 1), 304.8, 1e-3);
  // UTM in metres over NAVD88 heights in US survey feet (LAS 1.4, WKT): the vertical part decides,
  // and the output's CRS keeps only the horizontal part (its heights are metres now).
  const std::vector<LasPoint> utm = {{500000.5, 6400000.5, 1000.0, 0, 1, 1, 2}};
  LasWriteOptions compound;
  compound.version_minor = 4;
  compound.point_format = 6;
  compound.crs_wkt = wkt("EPSG:32633+6360");
  compound.offset[0] = 500000, compound.offset[1] = 6400000;
  write_las(dir + "/compound.las", utm, compound);
  DsmOptions c;
  c.points = {dir + "/compound.las"};
  c.te = std::array<double, 4>{500000, 6400000, 500002, 6400002};
  r = build_dsm(c);
  EXPECT_NEAR(r.dsm(0, 1), 1000.0 * kUsFoot, 1e-3);
  OGRSpatialReference written;
  ASSERT_EQ(written.importFromWkt(r.georef.crs_wkt.c_str()), OGRERR_NONE);
  EXPECT_FALSE(written.IsCompound());
  EXPECT_TRUE(written.IsProjected());
  // A DEM whose band says feet.
  GeoReference g;
  g.has_geotransform = true;
  g.geotransform = {500000, 1, 0, 6400004, 0, -1};
  g.crs_wkt = wkt("EPSG:32633");
  std::vector<float> z(16, 100.0f);
  write_bands(dir + "/dem_ft.tif", 4, 4, g, {{"height", "ft", z.data(), {}}}, {});
  DsmOptions dem;
  dem.dems = {dir + "/dem_ft.tif"};
  r = build_dsm(dem);
  EXPECT_NEAR(r.dsm(1, 1), 30.48, 1e-4);
  ASSERT_EQ(r.report.height_units.size(), 1u);
  EXPECT_NE(r.report.height_units[0].find("band unit 'ft'"), std::string::npos) << r.report.height_units[0];
}

// Footprint heights are attributes without a unit: metres, unless the layer's CRS is in another
// unit, where the user must say (NYC's footprints, in EPSG:2263, give roof heights in feet).
TEST(DsmBuilder, FootprintHeightsUnderAFeetCrsNeedTheirUnit) {
  const std::string dir = dir_for("footprint-feet");
  write_text(dir + "/ny.geojson", R"({"type":"FeatureCollection",
    "crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::2263"}},
    "features":[{"type":"Feature","properties":{"h":100},"geometry":{"type":"Polygon",
      "coordinates":[[[980000,200000],[980100,200000],[980100,200100],[980000,200100],[980000,200000]]]}}]})");
  DsmOptions d;
  d.footprints = dir + "/ny.geojson";
  d.height_field = "h";
  d.absolute_heights = true;
  d.res = 10.0;
  try {
    build_dsm(d);
    ADD_FAILURE() << "footprint heights under a feet CRS read without their unit";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--footprint-z-scale"), std::string::npos) << e.what();
  }
  d.footprint_z_scale = 0.3048;
  const DsmResult r = build_dsm(d);
  EXPECT_NEAR(r.dsm(5, 5), 30.48, 1e-4);
}

TEST(DsmBuilder, TheAutzenSampleInFeetBecomesMetres) {
  const std::string path = std::string(SKYVIEW_SHARED_DIR) + "/sample_data/las/autzen_geo_proj.las";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "../shared/sample_data is absent";
  DsmOptions d;
  d.points = {path};
  d.res = 5.0;  // feet, the CRS's unit
  const DsmResult r = build_dsm(d);
  // Its returns lie 407-537 ft up (GeoTIFF keys: Oregon Lambert in feet, no vertical keys).
  float lo = 1e9f, hi = -1e9f;
  for (const float v : r.dsm.values()) {
    if (std::isnan(v)) continue;
    lo = std::min(lo, v), hi = std::max(hi, v);
  }
  EXPECT_NEAR(lo, 407.35 * 0.3048, 0.01);
  EXPECT_NEAR(hi, 536.84 * 0.3048, 0.01);
}

TEST(DsmBuilder, RealLidarSampleGridsAllItsPoints) {
  const std::string path = std::string(SKYVIEW_SHARED_DIR) + "/sample_data/las/simple.las";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "../shared/sample_data is absent";
  DsmOptions d;
  d.points = {path};
  d.res = 2.0;
  d.t_srs = "EPSG:2994";  // the Autzen sample's Oregon Lambert (ft); the file itself carries no CRS
  const DsmResult r = build_dsm(d);
  EXPECT_EQ(r.report.points_read, 1065u);
  EXPECT_EQ(r.report.points_used, 1065u);
  EXPECT_GT(r.report.cells_from_points, 500);
  // simple1_3.las holds its unscaled integers as the header's min and max.
  const std::string raw = std::string(SKYVIEW_SHARED_DIR) + "/sample_data/las/simple1_3.las";
  DsmOptions e;
  e.points = {raw};
  e.res = 5.0;
  e.t_srs = "EPSG:32610";
  const DsmResult q = build_dsm(e);
  EXPECT_EQ(q.report.points_used, q.report.points_read);
  EXPECT_GT(q.report.points_read, 0u);
}

}  // namespace

TEST(DsmBuilder, SyntheticDistrictFromLidarAndFootprints) {
  const std::string dir = dir_for("district");
  const SyntheticDistrict d = synthetic_district(500000, 6400000, 96, 3);
  const std::string crs = wkt("EPSG:32633");
  LasWriteOptions lo;
  lo.crs_wkt = crs;
  lo.offset[0] = 500000, lo.offset[1] = 6400000;
  write_las(dir + "/d.las", district_lidar(d, 4.0, 5, 3), lo);
  write_district_footprints(dir + "/d.geojson", d, crs, false);
  DsmOptions o;
  o.points = {dir + "/d.las"};
  o.footprints = dir + "/d.geojson";
  o.height_field = "height";
  o.base_field = "base";
  o.denoise = true;
  o.res = 1.0;
  o.te = std::array<double, 4>{500000, 6400000, 500096, 6400096};
  const DsmResult r = build_dsm(o);
  EXPECT_EQ(r.report.footprints_burned, 8);
  EXPECT_EQ(r.report.footprints_from_cloud, 1);
  EXPECT_GE(r.report.points_removed_as_noise, 5u);
  auto cell_at = [&](double x, double y) { return r.dsm(static_cast<int>(x - 500000), static_cast<int>(6400096 - y)); };
  double top = 0;
  for (const DistrictBuilding& b : d.buildings) top = std::max(top, b.base + b.height);
  for (float v : r.dsm.values()) EXPECT_LE(v, top + 0.011) << "a bird survived";
  // South-west block: its footprint's top (the returns sit within 1 cm of it).
  const DistrictBuilding& sw = d.buildings[0];
  EXPECT_NEAR(cell_at(sw.outer[0][0] + 10.5, sw.outer[0][1] + 10.5), sw.base + sw.height, 0.011);
  // The courtyard of the middle block stays at the ground.
  const double cx = 500048.5, cy = 6400047.5;
  EXPECT_NEAR(cell_at(cx, cy), d.ground(cx, cy), 0.02);
  EXPECT_GT(cell_at(cx + 12, cy), d.ground(cx, cy) + 7.9);  // the ring of the block around it
  // The north-east block has no height: the 90th percentile of its roof returns gives it one.
  const DistrictBuilding& ne = d.buildings[8];
  ASSERT_FALSE(ne.height_known);
  EXPECT_NEAR(cell_at(ne.outer[0][0] + 10.5, ne.outer[0][1] + 10.5), ne.base + ne.height, 0.011);

  // Without a DEM or a base field, heights stand on the cloud's bare earth (its ground returns,
  // filled under the buildings), which --dtm writes.
  o.base_field.clear();
  o.want_dtm = true;
  const DsmResult rel = build_dsm(o);
  ASSERT_EQ(rel.dtm.size(), rel.dsm.size());
  EXPECT_EQ(rel.report.ground_source, "class 2");
  for (float v : rel.dtm.values()) ASSERT_FALSE(std::isnan(v));
  const double x = sw.outer[0][0] + 10.5, y = sw.outer[0][1] + 10.5;  // inside the south-west block
  const int c = static_cast<int>(x - 500000), row = static_cast<int>(6400096 - y);
  EXPECT_NEAR(rel.dtm(c, row), d.ground(x, y), 0.15);  // interpolated under the roof
  EXPECT_NEAR(rel.dsm(c, row), d.ground(x, y) + sw.height, 0.15);
  // Asking for the terrain does not change the DSM: a sparse survey leaves empty cells, which the
  // filled terrain must not close.
  write_las(dir + "/sparse.las", district_lidar(d, 0.3, 0, 5), lo);
  DsmOptions sparse;
  sparse.points = {dir + "/sparse.las"};
  sparse.res = 1.0;
  sparse.te = o.te;
  const DsmResult without = build_dsm(sparse);
  sparse.want_dtm = true;
  const DsmResult with = build_dsm(sparse);
  ASSERT_EQ(without.dsm.size(), with.dsm.size());
  std::size_t empty = 0;
  for (std::size_t k = 0; k < with.dsm.size(); ++k) {
    const float a = without.dsm.values()[k], b = with.dsm.values()[k];
    ASSERT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << k;
    empty += std::isnan(a);
  }
  EXPECT_GT(empty, with.dsm.size() / 4);
  for (float v : with.dtm.values()) ASSERT_FALSE(std::isnan(v));
  EXPECT_NEAR(rel.dtm(static_cast<int>(cx - 500000), static_cast<int>(6400096 - cy)), d.ground(cx, cy), 0.02);
  DsmOptions footprints_only;
  footprints_only.footprints = dir + "/d.geojson";
  footprints_only.height_field = "height";
  footprints_only.want_dtm = true;
  EXPECT_THROW(build_dsm(footprints_only), Error);
}
