#pragma once
// One input of load_scene, opened: what it is, the CRS it declares and where it lies, so that the
// scene's CRS and origin can be chosen before any mesh is made; then its meshes. One reader per
// format, each in its own file; load_scene (load_scene.cpp) is the one entry point that picks them.
#include <array>
#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include "scene/scene_assembly.h"
#include "skyview/scene/scene.h"

namespace skyview {

class SceneInput {
 public:
  virtual ~SceneInput() = default;
  // "CityJSON 2.0", "CityGML", "raster (GTiff)", "footprints (GPKG)", "mesh (glTF2)".
  virtual std::string format() const = 0;
  // The CRS the file states, as OGRSpatialReference::SetFromUserInput reads it (WKT, EPSG:n, an
  // OGC URN or URL); empty where it states none (a mesh, a CityJSON file without referenceSystem).
  virtual std::string declared_crs() const = 0;
  // Its bounds in its own coordinates (for the scene's origin); none when it holds no coordinates.
  virtual std::optional<std::array<Vec3d, 2>> extent() const = 0;
  // Rasters give the ground that footprints stand on, so they are added first.
  virtual bool is_ground() const { return false; }
  // Makes its meshes and hands them to `scene` (begin_input has been called).
  virtual void add_to(SceneAssembly& scene) = 0;
};

// Footprint layers (the first layer of any OGR vector source) extruded to prisms.
std::unique_ptr<SceneInput> open_footprints(const std::string& path, const SceneLoadOptions& options);
// DSM rasters (any GDAL raster with a geotransform), meshed as the ray cast meshes them.
std::unique_ptr<SceneInput> open_dsm(const std::string& path, const SceneLoadOptions& options);

// CityGML 1.0 and 2.0 through libcitygml; `head` holds the file's first bytes (its version).
std::unique_ptr<SceneInput> open_citygml(const std::string& path, const std::string& head,
                                         const SceneLoadOptions& options);
std::unique_ptr<SceneInput> open_citygml_text(const std::string& text, const std::string& name,
                                              const SceneLoadOptions& options);

// Mesh files through Assimp: whether it reads the extension, and the reader.
bool mesh_format_known(const std::string& path);
std::unique_ptr<SceneInput> open_mesh_file(const std::string& path, const SceneLoadOptions& options);
// From bytes in memory, `extension` (without the dot) telling the format (the fuzz target's way in),
// Assimp given `timeout_seconds` to read them (0: the time a file of that size gets).
std::unique_ptr<SceneInput> open_mesh_bytes(const std::string& bytes, const std::string& extension,
                                            const std::string& name, const SceneLoadOptions& options,
                                            double timeout_seconds = 0.0);

std::unique_ptr<SceneInput> open_cityjson(const std::string& path, const SceneLoadOptions& options);

// The first `bytes` of a file (fewer where it is shorter), for telling formats apart by content.
inline std::string file_start(const std::string& path, std::size_t bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string s(bytes, '\0');
  in.read(s.data(), static_cast<std::streamsize>(bytes));
  s.resize(static_cast<std::size_t>(in.gcount()));
  return s;
}
// The same for a document already in memory (the fuzz target's way in); `name` stands for the path.
std::unique_ptr<SceneInput> open_cityjson_text(const std::string& text, const std::string& name,
                                               const SceneLoadOptions& options);

}  // namespace skyview
