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
  std::string name;             // "building DEB_LOD2_...", "dsm city.tif", "model.obj:mesh 3"
  std::string source;           // the file it came from
  std::vector<Vec3f> vertices;  // relative to Scene::origin
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

// What one input gave: its format as read, its CRS, and what it held.
struct SceneInputReport {
  std::string path;
  std::string format;  // "CityJSON 2.0", "CityGML", "raster (GTiff)", "footprints (GPKG)", "mesh (glTF2)"
  std::string crs;     // the CRS its coordinates were read in (its name), "none (local metres)" without one
  std::int64_t meshes = 0, triangles = 0;  // kept
  std::int64_t meshes_skipped = 0, triangles_skipped = 0, surfaces_skipped = 0;
};

// What loading skipped, so a run can say it: never a crash, never a silent gap.
struct SceneReport {
  std::int64_t meshes_loaded = 0;
  std::int64_t meshes_skipped = 0;       // empty, NaN vertices, degenerate only
  std::int64_t triangles_skipped = 0;    // degenerate or non-finite triangles dropped from kept meshes
  std::int64_t surfaces_skipped = 0;     // polygons of a city model that made no triangle (no area, bad indices)
  std::vector<std::string> warnings;     // one line each, naming the file and object
  std::vector<SceneInputReport> inputs;  // in the order given
};

struct Scene {
  std::string crs_wkt;    // the projected CRS every mesh is in (empty: unknown, local metres)
  Vec3d origin{0, 0, 0};  // world coordinates of the local origin
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

  // CityJSON and CityGML: each object's geometries of the highest level of detail not above this
  // ("2", "2.2", "1"); empty: each object's highest.
  std::string lod;
  // Footprint layers, read as skyview dsm reads them (DsmOptions): prisms from the ground (the lowest
  // DSM/DEM input under the outline, else 0 with a warning) to the top.
  std::string height_field;        // building height attribute (required for a footprint layer)
  std::string base_field;          // absolute base height attribute: the prism's bottom
  bool absolute_heights = false;   // height_field is absolute, not above the ground
  double footprint_z_scale = 0.0;  // metres per field unit; 0: metres (refused for a layer in feet)
  // DSM rasters: metres per height unit; 0: from each raster (band unit, vertical CRS).
  double z_scale = 0.0;
  // DSM rasters: skirts on open edges, as the ray cast meshes them (surface_mesh.h).
  bool dsm_skirts = true;
  // Mesh files: which of the file's axes is up: "y" (turned to z: x east, -z north), "z" (as
  // stored); empty: by format (glTF, COLLADA and FBX as Assimp gives them: y; OBJ, PLY, STL, others: z).
  std::string up_axis;
};

// Loads and merges DSM rasters, footprint layers, CityGML, CityJSON and mesh files (by content and
// extension) into one scene. Throws skyview::Error (one line, naming the file) for inputs that
// cannot be read at all or a scene with no triangles; skipped objects are counted in Scene::report.
Scene load_scene(const std::vector<std::string>& inputs, const SceneLoadOptions& options = {});

}  // namespace skyview
