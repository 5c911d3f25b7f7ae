// CityGML into a scene through libcitygml: Berlin's LoD2 buildings against the file's envelope and
// its own closed shells, the hand-made LoD2 house (a 100 m cube under a 50 m gable), and small
// documents for what those do not hold.
#include <ogr_spatialref.h>

#include "scene_test_support.h"
#include "skyview/core/error.h"

using namespace skyview;
using namespace skyview::test;

namespace {

// A CityGML 2.0 document of `members` (cityObjectMember contents) with an envelope in `srs`.
std::string citygml(const std::string& srs, const std::string& members) {
  return R"(<?xml version="1.0" encoding="UTF-8"?>
<CityModel xmlns="http://www.opengis.net/citygml/2.0" xmlns:gml="http://www.opengis.net/gml"
           xmlns:bldg="http://www.opengis.net/citygml/building/2.0">
  <gml:boundedBy><gml:Envelope srsName=")" +
         srs + R"(" srsDimension="3">
    <gml:lowerCorner>500000 5800000 30</gml:lowerCorner><gml:upperCorner>500010 5800010 40</gml:upperCorner>
  </gml:Envelope></gml:boundedBy>
)" + members +
         "</CityModel>\n";
}

std::string building(const std::string& id, const std::string& pos_list) {
  return R"(<cityObjectMember><bldg:Building gml:id=")" + id + R"(">
  <bldg:lod1MultiSurface><gml:MultiSurface><gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing>
    <gml:posList>)" +
         pos_list +
         R"(</gml:posList>
  </gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember></gml:MultiSurface></bldg:lod1MultiSurface>
</bldg:Building></cityObjectMember>
)";
}

}  // namespace

TEST(SceneCityGml, BerlinLod2AgainstItsEnvelopeAndShells) {
  const std::string path = city3d_file("berlin_sample.citygml");
  REQUIRE_CITY3D(path);
  const Scene s = load_scene({path});
  EXPECT_EQ(s.meshes.size(), 61u);
  EXPECT_EQ(s.report.meshes_skipped, 0);
  // Each polygon of V corners and H holes gives V + 2H - 2 triangles (4881, counted from the
  // file), but for one roof whose courtyard touches its outline at a corner: one triangle fewer
  // (the touching corner is one point of the surface, not two).
  EXPECT_EQ(s.triangle_count(), 4879u);
  EXPECT_EQ(s.report.inputs[0].format, "CityGML 1.0");
  OGRSpatialReference crs;
  ASSERT_EQ(crs.importFromWkt(s.crs_wkt.c_str()), OGRERR_NONE);
  EXPECT_STREQ(crs.GetAuthorityCode(nullptr), "25833");
  const auto b = s.bounds();
  const double lower[3] = {390477.994899531, 5819214.18602785, 27.5200004577637};
  const double upper[3] = {390703.083850149, 5819552.649, 64.2225904352854};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(b[0][k] + s.origin[k], lower[k], 2e-3) << k;
    EXPECT_NEAR(b[1][k] + s.origin[k], upper[k], 2e-3) << k;
  }
  // 57 of the 61 buildings are closed shells in the file (every ring edge met once each way by
  // another ring); their meshes are closed, turned outward, the others are not.
  int closed = 0;
  for (const SceneMesh& m : s.meshes) {
    if (!watertight(m)) continue;
    ++closed;
    EXPECT_GT(enclosed_volume(m), 0.0) << m.name;
  }
  EXPECT_EQ(closed, 57);
  // A known building: ground at 31.98 m, ridge at 56.5 m.
  const SceneMesh* known = find_mesh(s, "Building BLDG_0003000e002837e8");
  ASSERT_NE(known, nullptr);
  EXPECT_TRUE(watertight(*known));
  float lo = 1e9f, hi = -1e9f;
  for (const Vec3f& v : known->vertices) lo = std::min(lo, v[2]), hi = std::max(hi, v[2]);
  EXPECT_NEAR(lo, 31.98, 1e-4);
  EXPECT_NEAR(hi, 56.5, 1e-4);

  SceneLoadOptions o;
  o.lod = "1";
  try {
    load_scene({path}, o);
    FAIL() << "Berlin's LoD2 loaded at LoD 1";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("at or below LoD 1"), std::string::npos) << e.what();
  }
}

TEST(SceneCityGml, Lod2HouseIsAClosedSolid) {
  const std::string path = city3d_file("cube_lod2.gml");
  REQUIRE_CITY3D(path);
  const Scene s = load_scene({path});
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_TRUE(s.crs_wkt.empty());
  EXPECT_EQ(s.report.inputs[0].format, "CityGML 2.0");
  const SceneMesh& m = s.meshes[0];
  EXPECT_TRUE(watertight(m));
  // 100 m cube and a gable 50 m high along it: 1e6 + 100 * 100 * 50 / 2 m³.
  EXPECT_NEAR(enclosed_volume(m), 1.25e6, 1.0);
  EXPECT_NEAR(upward_area(m), 1e4, 1e-2);
  EXPECT_NEAR(s.bounds()[1][2], 150.0, 1e-4);
}

TEST(SceneCityGml, AdvCrsNamesFlatPolygonsAndBrokenDocuments) {
  const std::string dir = temp_dir("citygml");
  const std::string path = dir + "/two.gml";
  write_text(path, citygml("urn:adv:crs:ETRS89_UTM32*DE_DHHN92_NH",
                           building("good", "500000 5800000 30 500010 5800000 30 500010 5800010 40 500000 5800000 30") +
                               building("flat",
                                        "500000 5800000 30 500005 5800000 30 500010 5800000 30 500000 "
                                        "5800000 30")));
  const Scene s = load_scene({path});
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].name, "Building good");
  EXPECT_EQ(s.report.meshes_skipped, 1);
  EXPECT_EQ(s.report.surfaces_skipped, 1);
  // The AdV's name for UTM 32N with DHHN92 heights: EPSG:25832 + 5783.
  OGRSpatialReference crs;
  ASSERT_EQ(crs.importFromWkt(s.crs_wkt.c_str()), OGRERR_NONE);
  EXPECT_TRUE(crs.IsCompound());
  EXPECT_NE(std::string(crs.GetName()).find("UTM zone 32N"), std::string::npos) << crs.GetName();
  EXPECT_NE(std::string(crs.GetName()).find("DHHN92"), std::string::npos) << crs.GetName();

  auto error_of = [&](const std::string& text) {
    const std::string bad = dir + "/bad.gml";
    write_text(bad, text);
    try {
      load_scene({bad});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("<CityModel xmlns=\"http://www.opengis.net/citygml/2.0\"><cityObjectMember>").find("as CityGML"),
            std::string::npos);
  EXPECT_NE(error_of("<CityModel xmlns=\"http://www.opengis.net/citygml/3.0\"></CityModel>").find("CityGML 3.0"),
            std::string::npos);
  EXPECT_NE(error_of(citygml("EPSG:25832", "")).find("hold no triangles"), std::string::npos);
}
