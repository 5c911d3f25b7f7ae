#pragma once
// A 3-D scene for camera views and shadow rays: triangle meshes from DSMs, extruded footprints,
// CityGML, CityJSON and mesh files (OBJ, PLY, glTF), all in one projected CRS. Vertices are stored
// relative to `origin` in float (a city's UTM coordinates need double; metres around a local
// origin do not), z up, in metres.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace skyview {

using Vec3f = std::array<float, 3>;
using Vec3d = std::array<double, 3>;

// One object of the scene (a building, a terrain tile, a mesh file's mesh): its triangles index
// its own vertices.
struct SceneMesh {
  std::string name;    // "building DEB_LOD2_...", "dsm city.tif", "model.obj:mesh 3"
  std::string source;  // the file it came from
  std::vector<Vec3f> vertices;                   // relative to Scene::origin
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

// What loading skipped, so a run can say it: never a crash, never a silent gap.
struct SceneReport {
  std::int64_t meshes_loaded = 0;
  std::int64_t meshes_skipped = 0;        // empty, NaN vertices, degenerate only
  std::int64_t triangles_skipped = 0;     // degenerate or non-finite triangles dropped from kept meshes
  std::vector<std::string> warnings;      // one line each, naming the file and object
};

struct Scene {
  std::string crs_wkt;       // the projected CRS every mesh is in (empty: unknown, local metres)
  Vec3d origin{0, 0, 0};     // world coordinates of the local origin
  std::vector<SceneMesh> meshes;
  SceneReport report;

  // Axis-aligned bounds of all vertices, relative to origin; lo > hi when empty.
  std::array<Vec3f, 2> bounds() const;
  std::size_t triangle_count() const;
};

// How inputs are brought into one scene (the loaders, src/scene/, fill in the rest).
struct SceneLoadOptions {
  std::string s_srs;  // CRS of inputs that carry none (a mesh file); empty: refuse mixing with georeferenced ones
  std::string t_srs;  // the scene's CRS; empty: the first georeferenced input's (must be projected, metres)
};

// Loads and merges DSM rasters, footprint layers, CityGML, CityJSON and mesh files (by content and
// extension) into one scene. Throws skyview::Error (one line, naming the file) for inputs that
// cannot be read at all or a scene with no triangles; skipped objects are counted in Scene::report.
Scene load_scene(const std::vector<std::string>& inputs, const SceneLoadOptions& options = {});

}  // namespace skyview
