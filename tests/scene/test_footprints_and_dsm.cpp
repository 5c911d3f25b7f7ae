// Footprints extruded to prisms and DSM rasters meshed as the ray cast meshes them: the synthetic
// district (whose every height is known) and the Gothenburg DSM of ../shared.
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>

#include "core/test_support.h"
#include "scene_test_support.h"
#include "skyview/core/error.h"
#include "skyview/horizon/surface_mesh.h"
#include "skyview/raster/raster_io.h"
#include "skyview/synthetic/synthetic_district.h"

using namespace skyview;
using namespace skyview::test;

namespace {

double ring_area(const std::vector<std::array<double, 2>>& r) {
  double a = 0;
  for (std::size_t k = 0; k < r.size(); ++k) {
    const auto &p = r[k], &q = r[(k + 1) % r.size()];
    a += p[0] * q[1] - q[0] * p[1];
  }
  return 0.5 * std::abs(a);
}

constexpr double kX0 = 500000, kY0 = 5800000;  // UTM 33N

struct District {
  SyntheticDistrict d = synthetic_district(kX0, kY0, 200.0);
  std::string footprints, ground;
};

// The district's footprints (GeoJSON) and its bare ground as a 1 m GeoTIFF, both in EPSG:25833.
District write_district(const std::string& dir) {
  District out;
  out.footprints = dir + "/footprints.geojson";
  write_district_footprints(out.footprints, out.d, wkt_of("EPSG:25833"), false);
  out.ground = dir + "/ground.tif";
  const int n = 220;  // 10 m beyond the district on each side
  Grid<float> z(n, n);
  GeoReference g;
  g.has_geotransform = true;
  g.geotransform = {kX0 - 10, 1, 0, kY0 + 210, 0, -1};
  g.crs_wkt = wkt_of("EPSG:25833");
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) z(c, r) = static_cast<float>(out.d.ground(g.x_of(c, r), g.y_of(c, r)));
  }
  write_bands(out.ground, n, n, g, {{"height", "metre", z.data(), {}}}, {});
  return out;
}

std::vector<const DistrictBuilding*> with_height(const SyntheticDistrict& d) {
  std::vector<const DistrictBuilding*> b;
  for (const DistrictBuilding& x : d.buildings) {
    if (x.height_known) b.push_back(&x);
  }
  return b;
}

}  // namespace

TEST(SceneFootprints, PrismsWithBaseFieldKeepAreaAndVolume) {
  const District district = write_district(temp_dir("footprints"));
  SceneLoadOptions o;
  o.height_field = "height";
  o.base_field = "base";
  const Scene s = load_scene({district.footprints}, o);
  const auto known = with_height(district.d);
  ASSERT_GT(known.size(), 3u);
  ASSERT_EQ(s.meshes.size(), known.size());
  EXPECT_EQ(s.report.meshes_skipped, static_cast<std::int64_t>(district.d.buildings.size() - known.size()));
  EXPECT_EQ(s.report.inputs[0].format, "footprints (GeoJSON)");
  int courtyards = 0;
  for (std::size_t i = 0; i < known.size(); ++i) {
    const DistrictBuilding& b = *known[i];
    const SceneMesh& m = s.meshes[i];
    const double area = ring_area(b.outer) - (b.courtyard.empty() ? 0.0 : ring_area(b.courtyard));
    courtyards += !b.courtyard.empty();
    EXPECT_TRUE(watertight(m)) << m.name;
    // The roof is the polygon (holes kept); the prism's volume, by the divergence theorem, is area x height.
    EXPECT_NEAR(upward_area(m), area, 1e-6 * area) << m.name;
    EXPECT_NEAR(enclosed_volume(m), area * b.height, 1e-5 * area * b.height) << m.name;
    float lo = 1e9f, hi = -1e9f;
    for (const Vec3f& v : m.vertices) lo = std::min(lo, v[2]), hi = std::max(hi, v[2]);
    EXPECT_NEAR(lo, b.base, 1e-4) << m.name;
    EXPECT_NEAR(hi, b.base + b.height, 1e-4) << m.name;
  }
  EXPECT_GT(courtyards, 0);
  // The footprints' CRS is the scene's.
  EXPECT_NE(s.crs_wkt.find("UTM zone 33N"), std::string::npos);
}

TEST(SceneFootprints, RelativeHeightsStandOnTheDsmOrOnZero) {
  const District district = write_district(temp_dir("footprints"));
  SceneLoadOptions o;
  o.height_field = "height";
  // Without a DSM: on 0 m, with a warning.
  const Scene bare = load_scene({district.footprints}, o);
  const auto known = with_height(district.d);
  ASSERT_EQ(bare.meshes.size(), known.size());
  std::string warnings;
  for (const std::string& w : bare.report.warnings) warnings += w + "\n";
  EXPECT_NE(warnings.find(std::to_string(known.size()) + " footprints stand on 0 m"), std::string::npos) << warnings;
  EXPECT_NEAR(bare.bounds()[0][2], 0.0, 1e-6);

  // With the ground raster (given after them): on the lowest ground along the outline, the west
  // side of the slope; the DSM's mesh comes first in the scene.
  const Scene s = load_scene({district.footprints, district.ground}, o);
  ASSERT_EQ(s.meshes.size(), known.size() + 1);
  EXPECT_EQ(s.meshes[0].name, "dsm ground.tif");
  for (std::size_t i = 0; i < known.size(); ++i) {
    const DistrictBuilding& b = *known[i];
    double west = 1e300;
    for (const auto& p : b.outer) west = std::min(west, p[0]);
    const double ground = district.d.ground(west, 0.0);
    const SceneMesh& m = s.meshes[i + 1];
    float lo = 1e9f, hi = -1e9f;
    for (const Vec3f& v : m.vertices) lo = std::min(lo, v[2]), hi = std::max(hi, v[2]);
    EXPECT_NEAR(lo, ground, 1e-3) << m.name;
    EXPECT_NEAR(hi, ground + b.height, 1e-3) << m.name;
  }
  for (const std::string& w : s.report.warnings) EXPECT_EQ(w.find("stand on 0 m"), std::string::npos) << w;
}

TEST(SceneFootprints, AthensTreesOnTheirTerrain) {
  const std::string dem = std::string(SKYVIEW_SHARED_DIR) + "/sample_data/city_athens/DEM.tif";
  const std::string trees = std::string(SKYVIEW_SHARED_DIR) + "/sample_data/city_athens/trees.gpkg";
  if (!std::filesystem::exists(trees)) GTEST_SKIP() << "../shared/sample_data is absent: real-data test skipped";
  SceneLoadOptions o;
  o.height_field = "height";
  const Scene s = load_scene({trees, dem}, o);
  ASSERT_EQ(s.meshes.size(), 7u);  // the terrain and six tree crowns
  EXPECT_TRUE(s.report.warnings.empty()) << s.report.warnings.front();
  // Each crown stands on the terrain and rises by its height field.
  GDALDatasetUniquePtr layer(GDALDataset::Open(trees.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  ASSERT_TRUE(layer);
  const Terrain t = read_terrain(dem, {});
  double lowest = 1e300, highest = -1e300;
  for (int r = 0; r < t.height(); ++r) {
    for (int c = 0; c < t.width(); ++c) {
      if (t.valid(c, r))
        lowest = std::min(lowest, t.absolute_height(c, r)), highest = std::max(highest, t.absolute_height(c, r));
    }
  }
  int checked = 0;
  for (auto& feature : *layer->GetLayer(0)) {
    const SceneMesh* m = find_mesh(s, "footprint " + std::to_string(feature->GetFID()));
    ASSERT_NE(m, nullptr) << feature->GetFID();
    EXPECT_TRUE(watertight(*m));
    float lo = 1e9f, hi = -1e9f;
    for (const Vec3f& v : m->vertices) lo = std::min(lo, v[2]), hi = std::max(hi, v[2]);
    EXPECT_NEAR(hi - lo, feature->GetFieldAsDouble("height"), 1e-4);
    EXPECT_GE(lo, lowest - 1e-3);
    EXPECT_LE(lo, highest + 1e-3);
    ++checked;
  }
  EXPECT_EQ(checked, 6);
}

TEST(SceneFootprints, BadLayersAndOptions) {
  const District district = write_district(temp_dir("footprints"));
  auto error_of = [](const std::vector<std::string>& in, const SceneLoadOptions& o) {
    try {
      load_scene(in, o);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  SceneLoadOptions o;
  EXPECT_NE(error_of({district.footprints}, o).find("give --height-field"), std::string::npos);
  o.height_field = "name";
  EXPECT_NE(error_of({district.footprints}, o).find("not numbers"), std::string::npos);
  o.height_field = "storeys";
  EXPECT_NE(error_of({district.footprints}, o).find("has no field 'storeys'"), std::string::npos);
  const std::string points = temp_dir("footprints") + "/points.geojson";
  write_text(points, R"({"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {"h": 3},
    "geometry": {"type": "Point", "coordinates": [1, 2]}}]})");
  o.height_field = "h";
  EXPECT_NE(error_of({points}, o).find("holds no polygons"), std::string::npos);
}

TEST(SceneDsm, MeshedAsTheRayCastMeshesIt) {
  const std::string dir = temp_dir("dsm");
  // 4 x 3 cells of 2 m, one nodata corner: 5 full quads and one half.
  const std::string path = dir + "/small.tif";
  Grid<float> z(4, 3);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float values[12] = {10, 11, 12, 13, 10, 11, 12, 13, 10, 11, 12, nan};
  std::copy(values, values + 12, z.data());
  GeoReference g;
  g.has_geotransform = true;
  g.geotransform = {300000, 2, 0, 6000006, 0, -2};
  g.crs_wkt = wkt_of("EPSG:32632");
  write_bands(path, 4, 3, g, {{"height", "metre", z.data(), {}}}, {});
  SceneLoadOptions o;
  o.dsm_skirts = false;
  const Scene flat = load_scene({path}, o);
  ASSERT_EQ(flat.meshes.size(), 1u);
  EXPECT_EQ(flat.triangle_count(), 2u * 5 + 1);
  EXPECT_EQ(flat.report.inputs[0].format, "raster (GTiff)");
  // Cell centres, from (301, 6000005) to (307, 6000001); every triangle faces up.
  const auto b = flat.bounds();
  EXPECT_NEAR(b[0][0] + flat.origin[0], 300001.0, 1e-6);
  EXPECT_NEAR(b[1][0] + flat.origin[0], 300007.0, 1e-6);
  EXPECT_NEAR(b[0][1] + flat.origin[1], 6000001.0, 1e-6);
  EXPECT_NEAR(b[1][1] + flat.origin[1], 6000005.0, 1e-6);
  EXPECT_NEAR(b[0][2], 10.0, 1e-5);
  EXPECT_NEAR(b[1][2], 13.0, 1e-5);
  for (const auto& t : flat.meshes[0].triangles) EXPECT_GT(normal_of(flat.meshes[0], t)[2], 0.0);
  // Surface area of the sloped surface: 1 m rise per 2 m run across, 5.5 quads of 4 m².
  EXPECT_NEAR(surface_area(flat.meshes[0]), 5.5 * 4.0 * std::sqrt(1.25), 1e-4);

  // With skirts (the default): ten cells down from every open edge, as surface_mesh hangs them
  // (cells of 2 m in the CRS, 1.9998 m on the ground 200 km west of the UTM zone's meridian).
  const Scene skirted = load_scene({path});
  const Terrain t = read_terrain(path, {});
  const double drop = 1000 * kSkirtOut * raster_centre_jacobian(t).min_cell_size();
  EXPECT_NEAR(drop, 20.0, 0.01);
  const SurfaceMesh reference = surface_mesh(t, 1.0, drop);
  EXPECT_EQ(skirted.triangle_count(), reference.triangles.size() / 3);
  EXPECT_NEAR(skirted.bounds()[0][2], 10.0 - drop, 1e-5);
}

TEST(SceneDsm, GothenburgDsmTriangleForTriangle) {
  const std::string path = std::string(SKYVIEW_SHARED_DIR) + "/sample_data/city_goteborg/DSM_KRbig.tif";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "../shared/sample_data is absent: real-data test skipped";
  const Scene s = load_scene({path});
  const Terrain t = read_terrain(path, {});
  const SurfaceMesh m = surface_mesh(t, 1.0, 1000 * kSkirtOut * raster_centre_jacobian(t).min_cell_size());
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.triangle_count(), m.triangles.size() / 3);
  EXPECT_EQ(s.report.triangles_skipped, 0);
  // Its highest vertex is the raster's highest cell.
  double highest = -1e300;
  for (int r = 0; r < t.height(); ++r) {
    for (int c = 0; c < t.width(); ++c) {
      if (t.valid(c, r)) highest = std::max(highest, t.absolute_height(c, r));
    }
  }
  EXPECT_NEAR(s.bounds()[1][2] + s.origin[2], highest, 1e-3);
}

TEST(SceneDsm, RasterWithoutGeoreferencingIsRefused) {
  const std::string path = temp_dir("dsm") + "/picture.png";
  const std::uint8_t pixels[4] = {1, 2, 3, 4};
  write_png(path, 2, 2, 1, pixels, false);
  try {
    load_scene({path});
    FAIL() << "a PNG without georeferencing was meshed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("without georeferencing"), std::string::npos) << e.what();
  }
}
