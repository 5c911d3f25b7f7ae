// Mesh files through Assimp: Debian's assimp-testmodels (skipped where absent), small files written
// here for the axes, bad meshes and placing a mesh among georeferenced models.
#include <filesystem>

#include "scene_test_support.h"
#include "skyview/core/error.h"

using namespace skyview;
using namespace skyview::test;

namespace {

std::string test_model(const std::string& relative) {
  const std::string path = "/usr/share/assimp/models/" + relative;
  return std::filesystem::exists(path) ? path : std::string();
}

#define REQUIRE_MODEL(path) \
  if ((path).empty()) GTEST_SKIP() << "assimp-testmodels is not installed: test skipped"

std::string base64(const std::string& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const unsigned n = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (i + 1 < bytes.size() ? static_cast<unsigned char>(bytes[i + 1]) << 8 : 0) |
                       (i + 2 < bytes.size() ? static_cast<unsigned char>(bytes[i + 2]) : 0);
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[n & 63] : '=';
  }
  return out;
}

// A glTF 2.0 file of one triangle with the given corners (its buffer embedded as a data URI).
std::string gltf_triangle(const float (&p)[9]) {
  const std::string data(reinterpret_cast<const char*>(p), sizeof p);
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)" +
         base64(data) + R"("}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [)" +
         std::to_string(std::min({p[0], p[3], p[6]})) + "," + std::to_string(std::min({p[1], p[4], p[7]})) + "," +
         std::to_string(std::min({p[2], p[5], p[8]})) + R"(], "max": [)" +
         std::to_string(std::max({p[0], p[3], p[6]})) + "," + std::to_string(std::max({p[1], p[4], p[7]})) + "," +
         std::to_string(std::max({p[2], p[5], p[8]})) + "]}]}";
}

// A binary PLY on which Debian's Assimp 5.2 crashes (SIGSEGV in its PLY parser).
const char kAssimpCrashingPly[] =
    "\x70\x6c\x79\x0a\x66\x6f\x72\x6d\x61\x74\x20\x62\x69\x6e\x61\x72\x79\x5f\x30\x0a\x0a\x6f\x20\x31"
    "\x0a\x0a\x23\x20\x56\x65\x72\x74\x65\x78\x20\x6c\x69\x73\x74\x0a\x0a\x76\x20\x2d\x30\x2e\x35\x20"
    "\x2d\x30\x2e\x35\x20\x30\x2e\x35\x0a\x76\x20\x2d\x30\x0a\x65\x6e\x64\x5f\x68\x65\x61\x64\x65\x72"
    "\x69\x6e\x74\x2f\x4c\x69\x6e\x65\x2f\x46\x61\x63\x65\x20\x6c\x69\x73\x74\x0a\x0a\x75\x73\x65\x6d"
    "\x00\x00\x00\x03\x00\x00\x00\x03\x03\x00\x00\x00\x07\x00\x00\x00\x04\x00\x00\x00\x03\x03\x00\x00"
    "\x00\x04\x00\x00\x00\x00\x00\x00\x00";

std::string error_of(const std::vector<std::string>& inputs, const SceneLoadOptions& o = {}) {
  try {
    load_scene(inputs, o);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(SceneMeshFiles, DebianTestModelsAreClosedUnitCubes) {
  const std::string obj = test_model("OBJ/box.obj"), ply = test_model("PLY/cube.ply");
  REQUIRE_MODEL(obj);
  for (const std::string& path : {obj, ply}) {
    const Scene s = load_scene({path});
    ASSERT_EQ(s.meshes.size(), 1u) << path;
    EXPECT_EQ(s.triangle_count(), 12u) << path;
    EXPECT_TRUE(s.crs_wkt.empty());
    EXPECT_TRUE(watertight(s.meshes[0])) << path;
    EXPECT_NEAR(std::abs(enclosed_volume(s.meshes[0])), 1.0, 1e-6) << path;
    const auto b = s.bounds();
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(b[1][k] - b[0][k], 1.0, 1e-6) << path;
  }
  EXPECT_EQ(load_scene({ply}).report.inputs[0].format, "mesh (PLY, z up)");
  // The PLY cube spans 0..1 on each axis: its corner is where the file puts it, whatever the origin.
  const Scene s = load_scene({ply});
  EXPECT_NEAR(s.bounds()[0][0] + s.origin[0], 0.0, 1e-6);
  EXPECT_NEAR(s.bounds()[1][2] + s.origin[2], 1.0, 1e-6);
}

TEST(SceneMeshFiles, GltfIsTurnedFromYUpToZUp) {
  const std::string dir = temp_dir("mesh");
  const std::string path = dir + "/tri.gltf";
  // In glTF's axes: 10 m up (y), 5 m towards -z (north once turned).
  const float p[9] = {0, 10, -5, 4, 10, -5, 0, 10, -9};
  write_text(path, gltf_triangle(p));
  const Scene s = load_scene({path});
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.report.inputs[0].format, "mesh (GLTF, y up)");
  const auto b = s.bounds();
  EXPECT_NEAR(b[0][2] + s.origin[2], 10.0, 1e-6);  // up
  EXPECT_NEAR(b[1][2] + s.origin[2], 10.0, 1e-6);
  EXPECT_NEAR(b[0][1] + s.origin[1], 5.0, 1e-6);  // -z is north
  EXPECT_NEAR(b[1][1] + s.origin[1], 9.0, 1e-6);
  EXPECT_NEAR(b[1][0] + s.origin[0], 4.0, 1e-6);  // x stays east
  // The triangle turns counter-clockwise seen from +y in glTF: it faces up once turned.
  EXPECT_GT(normal_of(s.meshes[0], s.meshes[0].triangles[0])[2], 0.0);

  SceneLoadOptions o;
  o.up_axis = "z";  // as stored
  const Scene as_stored = load_scene({path}, o);
  EXPECT_NEAR(as_stored.bounds()[0][1] + as_stored.origin[1], 10.0, 1e-6);
  EXPECT_NEAR(as_stored.bounds()[0][2] + as_stored.origin[2], -9.0, 1e-6);
  o.up_axis = "x";
  EXPECT_NE(error_of({path}, o).find("y or z"), std::string::npos);

  const std::string box = test_model("glTF2/BoxTextured-glTF/BoxTextured.gltf");
  REQUIRE_MODEL(box);
  const Scene boxed = load_scene({box});
  EXPECT_EQ(boxed.triangle_count(), 12u);
  EXPECT_TRUE(watertight(boxed.meshes[0]));
}

TEST(SceneMeshFiles, BadMeshesAreCountedAndSkipped) {
  const std::string dir = temp_dir("mesh");
  // A NaN corner: its triangle goes, the other stays.
  write_text(dir + "/nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n");
  const Scene s = load_scene({dir + "/nan.obj"});
  EXPECT_EQ(s.triangle_count(), 1u);
  EXPECT_EQ(s.report.triangles_skipped, 1);
  // Two objects, one of them flat: one mesh, one skipped.
  write_text(dir + "/mixed.obj", "o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\no b\nv 5 5 5\nv 6 5 5\nv 7 5 5\nf 4 5 6\n");
  const Scene mixed = load_scene({dir + "/mixed.obj"});
  EXPECT_EQ(mixed.meshes.size(), 1u);
  EXPECT_EQ(mixed.report.meshes_skipped, 1);
  ASSERT_FALSE(mixed.report.warnings.empty());
  EXPECT_NE(mixed.report.warnings[0].find("only degenerate triangles ('mixed.obj:b')"), std::string::npos)
      << mixed.report.warnings[0];
  // Nothing left: one-line errors that say why.
  write_text(dir + "/flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  EXPECT_NE(error_of({dir + "/flat.obj"}).find("only degenerate triangles"), std::string::npos);
  write_text(dir + "/lines.obj", "v 0 0 0\nv 1 0 0\nv 2 1 0\nl 1 2 3\n");
  EXPECT_NE(error_of({dir + "/lines.obj"}).find("points or lines only"), std::string::npos);
  write_text(dir + "/short.obj", "# nothing\n");
  EXPECT_NE(error_of({dir + "/short.obj"}).find("cannot read"), std::string::npos);
  // Assimp 5.2 loops for ever on a PLY header without end_header, and dies of SIGSEGV on this
  // one (found by fuzz_mesh_reader): one-line errors, the process alive.
  write_text(dir + "/truncated.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n0 0 0\n");
  EXPECT_NE(error_of({dir + "/truncated.ply"}).find("not a complete PLY file"), std::string::npos);
  const std::string crashing(kAssimpCrashingPly, sizeof kAssimpCrashingPly - 1);
  write_text(dir + "/crashing.ply", crashing);
  EXPECT_NE(error_of({dir + "/crashing.ply"}).find("Assimp crashed (signal"), std::string::npos)
      << error_of({dir + "/crashing.ply"});
  const std::string infinite = test_model("glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb");
  REQUIRE_MODEL(infinite);
  EXPECT_NE(error_of({infinite}).find("only non-finite vertices"), std::string::npos);
}

TEST(SceneMeshFiles, PlacedAmongGeoreferencedModelsWithSSrs) {
  const std::string berlin = city3d_file("berlin_sample.citygml");
  REQUIRE_CITY3D(berlin);
  const std::string dir = temp_dir("mesh");
  // A 10 m square at 40 m in Berlin's UTM coordinates.
  const std::string obj = dir + "/kiosk.obj";
  write_text(obj, "v 390590 5819380 40\nv 390600 5819380 40\nv 390600 5819390 40\nv 390590 5819390 40\nf 1 2 3 4\n");
  EXPECT_NE(error_of({berlin, obj}).find("'" + obj + "' carries no CRS"), std::string::npos);
  SceneLoadOptions o;
  o.s_srs = "EPSG:25833";
  const Scene s = load_scene({berlin, obj}, o);
  ASSERT_EQ(s.meshes.size(), 62u);
  const SceneMesh& kiosk = s.meshes.back();
  EXPECT_EQ(kiosk.name, "kiosk.obj:defaultobject");
  for (const Vec3f& v : kiosk.vertices) {
    EXPECT_GE(v[0] + s.origin[0], 390590.0 - 0.5);  // Assimp's floats: steps of 0.5 m at 5.8e6
    EXPECT_LE(v[1] + s.origin[1], 5819390.0 + 0.5);
  }
  EXPECT_NEAR(upward_area(kiosk), 100.0, 10.0);
  bool warned = false;
  for (const std::string& w : s.report.warnings)
    warned |= w.find("single precision: steps of 0.5") != std::string::npos;
  EXPECT_TRUE(warned);
}
