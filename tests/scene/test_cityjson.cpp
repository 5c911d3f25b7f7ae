// CityJSON into a scene: the real Zürich (1.1, LoD2) and Delft (2.0, terrain with bridges) models
// against their own stated extents and attributes, and small hand-written files for what those do
// not hold (holes, closed solids, LoD choice, templates, 1.0, CityJSONSeq, broken content).
#include <ogr_spatialref.h>

#include <algorithm>

#include "scene_test_support.h"
#include "skyview/core/error.h"

using namespace skyview;
using namespace skyview::test;

namespace {

std::string authority_code(const std::string& wkt) {
  OGRSpatialReference s;
  if (s.importFromWkt(wkt.c_str()) != OGRERR_NONE) return "";
  const char* code = s.GetAuthorityCode(nullptr);
  return code ? code : "";
}

// A 20 x 10 m block with a 4 x 4 m courtyard, 7 m high, as one closed Solid (LoD 2), and the same
// block without courtyard, 5 m high (LoD 1). Integer vertices, scaled by 0.5 and moved to
// (1000, 2000, 3).
const char* kCourtyardBlock = R"({
  "type": "CityJSON", "version": "2.0",
  "transform": {"scale": [0.5, 0.5, 0.5], "translate": [1000, 2000, 3]},
  "metadata": {"referenceSystem": "https://www.opengis.net/def/crs/EPSG/0/25833"},
  "CityObjects": {
    "block": {"type": "Building", "geometry": [
      {"type": "Solid", "lod": "2", "boundaries": [[
        [[0, 3, 2, 1], [4, 5, 6, 7]],
        [[8, 9, 10, 11], [15, 14, 13, 12]],
        [[0, 1, 9, 8]], [[1, 2, 10, 9]], [[2, 3, 11, 10]], [[3, 0, 8, 11]],
        [[4, 12, 13, 5]], [[5, 13, 14, 6]], [[6, 14, 15, 7]], [[7, 15, 12, 4]]
      ]]},
      {"type": "Solid", "lod": "1", "boundaries": [[
        [[0, 3, 2, 1]], [[16, 17, 18, 19]],
        [[0, 1, 17, 16]], [[1, 2, 18, 17]], [[2, 3, 19, 18]], [[3, 0, 16, 19]]
      ]]}
    ]}
  },
  "vertices": [
    [0, 0, 0], [40, 0, 0], [40, 20, 0], [0, 20, 0],
    [16, 4, 0], [24, 4, 0], [24, 12, 0], [16, 12, 0],
    [0, 0, 14], [40, 0, 14], [40, 20, 14], [0, 20, 14],
    [16, 4, 14], [24, 4, 14], [24, 12, 14], [16, 12, 14],
    [0, 0, 10], [40, 0, 10], [40, 20, 10], [0, 20, 10]
  ]
})";

}  // namespace

TEST(SceneCityJson, ZurichLod2AgainstItsStatedExtent) {
  const std::string path = city3d_file("zurich_subset_lod2.city.json");
  REQUIRE_CITY3D(path);
  const Scene s = load_scene({path});
  // 161 BuildingParts carry the LoD2 surfaces; their 49 parent Buildings hold none and are no gap.
  EXPECT_EQ(s.meshes.size(), 161u);
  EXPECT_EQ(s.report.meshes_skipped, 0);
  EXPECT_EQ(s.report.surfaces_skipped, 0);
  // Each polygon of V corners and H holes gives V + 2H - 2 triangles (counted from the file).
  EXPECT_EQ(s.triangle_count(), 5142u);
  EXPECT_EQ(authority_code(s.crs_wkt), "2056");
  ASSERT_EQ(s.report.inputs.size(), 1u);
  EXPECT_EQ(s.report.inputs[0].format, "CityJSON 1.1");
  // The origin: the stated extent's centre in whole metres; the bounds: that extent.
  EXPECT_EQ(s.origin[0], 2682812.0);
  EXPECT_EQ(s.origin[1], 1248058.0);
  EXPECT_EQ(s.origin[2], 0.0);
  const auto b = s.bounds();
  const double stated[6] = {2678219.194, 1243078.725, 395.786, 2687404.734, 1253037.77, 620.905};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(b[0][k] + s.origin[k], stated[k], 2e-3) << k;
    EXPECT_NEAR(b[1][k] + s.origin[k], stated[k + 3], 2e-3) << k;
  }
  // Triangulation keeps every surface's area (Newell's areas of the file's polygons, holes
  // subtracted: 62309.844 m² in all, 1700.783 m² for one part).
  double area = 0;
  for (const SceneMesh& m : s.meshes) area += surface_area(m);
  EXPECT_NEAR(area, 62309.844, 0.05);
  const SceneMesh* part = find_mesh(s, "BuildingPart UUID_f5697b2b-4cd0-42c9-b96d-ed29ac5f9817");
  ASSERT_NE(part, nullptr);
  EXPECT_NEAR(surface_area(*part), 1700.783, 0.01);
}

TEST(SceneCityJson, DelftTerrainBridgesAndBuildings) {
  const std::string path = city3d_file("delft.city.json");
  REQUIRE_CITY3D(path);
  const Scene s = load_scene({path});
  EXPECT_EQ(s.meshes.size(), 570u);
  // Two surfaces of one object are flat (all corners on a line): made no triangle, counted.
  EXPECT_EQ(s.report.surfaces_skipped, 2);
  EXPECT_EQ(s.triangle_count(), 36269u);
  EXPECT_EQ(std::count_if(s.meshes.begin(), s.meshes.end(),
                          [](const SceneMesh& m) { return m.name.rfind("Bridge ", 0) == 0; }),
            3);
  EXPECT_EQ(authority_code(s.crs_wkt), "7415");  // RD New + NAP height, compound
  const auto b = s.bounds();
  const double stated[6] = {84616.468, 447422.999, -0.452, 85140.839, 447750.636, 16.846};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(b[0][k] + s.origin[k], stated[k], 1e-3) << k;
    EXPECT_NEAR(b[1][k] + s.origin[k], stated[k + 3], 1e-3) << k;
  }
  // A known building: measuredHeight 6 m (its roof, NAP) over min-height-surface -0.1 m.
  const SceneMesh* building = find_mesh(s, "Building b1105d28c-00ba-11e6-b420-2bdcc4ab5d7f");
  ASSERT_NE(building, nullptr);
  float lo = 1e9f, hi = -1e9f;
  for (const Vec3f& v : building->vertices) lo = std::min(lo, v[2]), hi = std::max(hi, v[2]);
  EXPECT_NEAR(hi, 6.0, 1e-4);
  EXPECT_NEAR(lo, -0.1, 1e-4);
}

TEST(SceneCityJson, ClosedSolidWithCourtyardAndLodChoice) {
  const std::string dir = temp_dir("cityjson");
  const std::string path = dir + "/block.city.json";
  write_text(path, kCourtyardBlock);
  const Scene s = load_scene({path});
  ASSERT_EQ(s.meshes.size(), 1u);
  const SceneMesh& m = s.meshes[0];
  EXPECT_EQ(m.name, "Building block");
  // LoD 2 by default: 20 x 10 m less a 4 x 4 m courtyard, 7 m high, closed and turned outward.
  EXPECT_TRUE(watertight(m));
  EXPECT_NEAR(upward_area(m), 184.0, 1e-4);
  EXPECT_NEAR(enclosed_volume(m), 184.0 * 7.0, 1e-3);
  EXPECT_EQ(authority_code(s.crs_wkt), "25833");
  EXPECT_NEAR(s.bounds()[0][0] + s.origin[0], 1000.0, 1e-6);
  EXPECT_NEAR(s.bounds()[1][2] + s.origin[2], 10.0, 1e-6);

  SceneLoadOptions o;
  o.lod = "1.5";  // the highest not above it: LoD 1, the 5 m box
  const Scene lod1 = load_scene({path}, o);
  ASSERT_EQ(lod1.meshes.size(), 1u);
  EXPECT_TRUE(watertight(lod1.meshes[0]));
  EXPECT_NEAR(enclosed_volume(lod1.meshes[0]), 200.0 * 5.0, 1e-3);
  EXPECT_EQ(lod1.triangle_count(), 12u);

  o.lod = "0";
  try {
    load_scene({path}, o);
    FAIL() << "a scene with no object at LoD 0 loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("without geometry at or below LoD 0"), std::string::npos) << e.what();
  }
  o.lod = "two";
  EXPECT_THROW(load_scene({path}, o), Error);
}

TEST(SceneCityJson, Version10TemplatesAndNoTransform) {
  const std::string dir = temp_dir("cityjson");
  const std::string path = dir + "/tree.json";
  // 1.0: real coordinates, numeric lod, an EPSG URN; a 1 x 1 m square template placed twice its
  // size at vertex 0.
  write_text(path, R"({"type": "CityJSON", "version": "1.0",
    "metadata": {"referenceSystem": "urn:ogc:def:crs:EPSG::2056"},
    "CityObjects": {"t1": {"type": "SolitaryVegetationObject", "geometry": [
      {"type": "GeometryInstance", "template": 0, "boundaries": [0],
       "transformationMatrix": [2,0,0,0, 0,2,0,0, 0,0,2,0, 0,0,0,1]}]}},
    "vertices": [[2600000.5, 1200000.25, 410.0]],
    "geometry-templates": {"templates": [{"type": "MultiSurface", "lod": 1, "boundaries": [[[0, 1, 2, 3]]]}],
      "vertices-templates": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]}})");
  const Scene s = load_scene({path});
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.report.inputs[0].format, "CityJSON 1.0");
  EXPECT_EQ(authority_code(s.crs_wkt), "2056");
  const auto b = s.bounds();
  EXPECT_NEAR(b[0][0] + s.origin[0], 2600000.5, 1e-6);
  EXPECT_NEAR(b[1][0] + s.origin[0], 2600002.5, 1e-6);
  EXPECT_NEAR(b[1][1] + s.origin[1], 1200002.25, 1e-6);
  EXPECT_NEAR(b[0][2], 410.0, 1e-4);
  EXPECT_NEAR(upward_area(s.meshes[0]), 4.0, 1e-5);
}

TEST(SceneCityJson, SequenceOfFeatures) {
  const std::string dir = temp_dir("cityjson");
  const std::string path = dir + "/two.city.jsonl";
  write_text(path,
             "{\"type\":\"CityJSON\",\"version\":\"2.0\",\"transform\":{\"scale\":[0.01,0.01,0.01],"
             "\"translate\":[0,0,0]},\"CityObjects\":{},\"vertices\":[]}\n"
             "{\"type\":\"CityJSONFeature\",\"id\":\"a\",\"CityObjects\":{\"a\":{\"type\":\"Building\","
             "\"geometry\":[{\"type\":\"MultiSurface\",\"lod\":\"1\",\"boundaries\":[[[0,1,2]]]}]}},"
             "\"vertices\":[[0,0,0],[100,0,0],[0,100,0]]}\n"
             "{\"type\":\"CityJSONFeature\",\"id\":\"b\",\"CityObjects\":{\"b\":{\"type\":\"Building\","
             "\"geometry\":[{\"type\":\"MultiSurface\",\"lod\":\"1\",\"boundaries\":[[[0,1,2,3]]]}]}},"
             "\"vertices\":[[500,0,0],[700,0,0],[700,200,0],[500,200,0]]}\n");
  const Scene s = load_scene({path});
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(s.report.inputs[0].format, "CityJSONSeq 2.0");
  EXPECT_EQ(s.triangle_count(), 3u);
  EXPECT_TRUE(s.crs_wkt.empty());  // no referenceSystem: local metres
  EXPECT_NEAR(upward_area(*find_mesh(s, "Building b")), 4.0, 1e-5);
}

TEST(SceneCityJson, BrokenContentIsCountedNotFatal) {
  const std::string dir = temp_dir("cityjson");
  const std::string path = dir + "/broken.json";
  write_text(path, R"({"type": "CityJSON", "version": "2.0",
    "transform": {"scale": [1, 1, 1], "translate": [0, 0, 0]},
    "CityObjects": {
      "good": {"type": "Building", "geometry": [{"type": "MultiSurface", "lod": "1",
        "boundaries": [[[0, 1, 2]], [[0, 1, 99]], [[0, 5, 1]]]}]},
      "flat": {"type": "Building", "geometry": [{"type": "MultiSurface", "lod": "1",
        "boundaries": [[[0, 1, 3]]]}]},
      "lines": {"type": "Road", "geometry": [{"type": "MultiLineString", "lod": "1", "boundaries": [[0, 1]]}]},
      "odd": {"type": "Building", "geometry": [{"type": "Tetrahedron", "lod": "1", "boundaries": []}]},
      "bare": {"type": "Building"}
    },
    "vertices": [[0, 0, 0], [10, 0, 0], [0, 10, 0], [20, 0, 0], [1, 1], ["x", 0, 0]]})");
  const Scene s = load_scene({path});
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.triangle_count(), 1u);
  // Index 99 is out of range; vertex 5 is not three numbers; [0, 1, 3] lies on a line.
  EXPECT_EQ(s.report.surfaces_skipped, 3);
  EXPECT_EQ(s.report.meshes_skipped, 4);  // flat, lines, odd, bare
  std::string all;
  for (const std::string& w : s.report.warnings) all += w + "\n";
  EXPECT_NE(all.find("2 vertices are not three numbers"), std::string::npos) << all;
  EXPECT_NE(all.find("geometry type Tetrahedron"), std::string::npos) << all;
  EXPECT_NE(all.find("without geometry ('Building bare')"), std::string::npos) << all;
}

TEST(SceneCityJson, BadFilesGiveOneLineErrors) {
  const std::string dir = temp_dir("cityjson");
  auto error_of = [&](const std::string& text) {
    const std::string path = dir + "/bad.city.json";
    write_text(path, text);
    try {
      load_scene({path});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("{\"type\": \"CityJSON\", \"version\": \"2.0\", ").find("not valid JSON"), std::string::npos);
  EXPECT_NE(error_of(R"({"type": "CityJSON", "version": "3.0", "CityObjects": {}, "vertices": []})")
                .find("versions 1.0, 1.1 and 2.0"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"type": "CityJSON", "version": "2.0", "CityObjects": {}, "vertices": []})")
                .find("without the \"transform\""),
            std::string::npos);
  EXPECT_NE(error_of(R"({"type": "CityJSON", "version": "1.1", "transform": {"scale": [0, 1, 1],
                         "translate": [0, 0, 0]}, "CityObjects": {}, "vertices": []})")
                .find("three finite scales"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"type": "CityJSON", "version": "2.0", "transform": {"scale": [1, 1, 1],
                         "translate": [0, 0, 0]}, "CityObjects": {}, "vertices": []})")
                .find("hold no triangles"),
            std::string::npos);
  EXPECT_NE(error_of(R"({"type": "CityJSON", "version": "2.0", "transform": {"scale": [1, 1, 1],
                         "translate": [0, 0, 0]}, "metadata": {"referenceSystem": "EPSG:99999999"},
                         "CityObjects": {}, "vertices": []})")
                .find("cannot understand the CRS"),
            std::string::npos);
  EXPECT_NE(error_of("").find("is empty"), std::string::npos);
  // A number past the range of a double is nlohmann's out_of_range, not a parse_error (found by the fuzzer).
  EXPECT_NE(error_of(R"({"type": "CityJSON", "version": "2.0", "transform": {"scale": [0.38E600, 1, 1],
                         "translate": [0, 0, 0]}, "CityObjects": {}, "vertices": []})")
                .find("not valid JSON"),
            std::string::npos);
}

TEST(SceneCityJson, RotterdamWithoutCrsAndMixedInputs) {
  const std::string rotterdam = city3d_file("rotterdam_subset.city.json");
  const std::string zurich = city3d_file("zurich_subset_lod2.city.json");
  REQUIRE_CITY3D(rotterdam);
  // Alone: local metres.
  const Scene local = load_scene({rotterdam});
  EXPECT_TRUE(local.crs_wkt.empty());
  EXPECT_EQ(local.meshes.size(), 16u);
  EXPECT_EQ(local.report.inputs[0].crs, "none (local metres)");
  // Beside a georeferenced model it needs --s_srs.
  try {
    load_scene({zurich, rotterdam});
    FAIL() << "a model without CRS was placed among georeferenced ones";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("carries no CRS"), std::string::npos) << e.what();
  }
  SceneLoadOptions o;
  o.s_srs = "EPSG:28992";
  const Scene rd = load_scene({rotterdam}, o);
  EXPECT_EQ(authority_code(rd.crs_wkt), "28992");
  EXPECT_EQ(rd.triangle_count(), local.triangle_count());
  // A geographic scene CRS is refused with the UTM zone to use instead.
  o.t_srs = "EPSG:4326";
  try {
    load_scene({rotterdam}, o);
    FAIL() << "a geographic scene CRS was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not in a projected CRS"), std::string::npos) << e.what();
  }
  // Reprojected (RD New to UTM 31N): the same buildings, areas within the two projections' scale
  // difference (RD's 0.9999079 and UTM's 0.9996 at the central meridian: under 0.2 %).
  o.t_srs = "EPSG:32631";
  const Scene utm = load_scene({rotterdam}, o);
  ASSERT_EQ(utm.meshes.size(), rd.meshes.size());
  double a_rd = 0, a_utm = 0;
  for (const SceneMesh& m : rd.meshes) a_rd += surface_area(m);
  for (const SceneMesh& m : utm.meshes) a_utm += surface_area(m);
  EXPECT_NEAR(a_utm / a_rd, 1.0, 2e-3);
  EXPECT_GT(utm.origin[1], 5.7e6);  // UTM northing at 51.9° N
}
