#pragma once
// What a loaded scene is, for people and for programs: a summary (meshes, triangles, bounds, CRS,
// what each input gave and what was skipped) as JSON, and the merged scene as a PLY file to check
// in a viewer (MeshLab, CloudCompare, Blender).
#include <nlohmann/json.hpp>

#include <string>

#include "skyview/scene/scene.h"

namespace skyview {

// {"meshes", "triangles", "crs" (name), "crs_wkt", "origin" [x, y, z], "bounds" {"min", "max"} in
// the scene's CRS (origin added), "skipped" {"meshes", "surfaces", "triangles"}, "inputs" [{"path",
// "format", "crs", "meshes", "triangles", "meshes_skipped", "surfaces_skipped",
// "triangles_skipped"}], "warnings" [...]}.
nlohmann::json scene_summary(const Scene& scene);

// Binary little-endian PLY of every mesh merged: float vertices relative to the scene's origin
// (stated in a comment with the CRS: viewers handle floats near zero best), triangles as vertex
// lists. Written under a temporary name and renamed into place; throws skyview::Error if `path`
// exists and !overwrite, or if writing fails.
void write_scene_ply(const Scene& scene, const std::string& path, bool overwrite);

}  // namespace skyview
