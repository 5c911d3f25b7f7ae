#pragma once
// Where every scene reader puts its meshes: the scene's CRS and origin, the checks that drop bad
// triangles and meshes (counted, with one warning line per input and reason, never a crash), and the
// ground that footprint prisms stand on.
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "skyview/scene/scene.h"

class OGRCoordinateTransformation;

namespace skyview {

// One object as a reader makes it: vertices in double, in its input's CRS (or the scene's, see
// SceneAssembly::add), before any check.
struct SourceMesh {
  std::string name;
  std::vector<Vec3d> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

// The lowest ground along points in the scene's CRS (x, y; z unused), NaN where the source has none.
using GroundSampler = std::function<double(const std::vector<Vec3d>&)>;

class SceneAssembly {
 public:
  // Fills `scene` (its crs_wkt and origin set by the caller).
  explicit SceneAssembly(Scene& scene) : scene_(scene) {}

  // Starts the meshes of one input: `to_scene` takes its coordinates to the scene's CRS (null: they
  // are in it). `report` names the input, its format and CRS; the counts are filled here.
  void begin_input(const SceneInputReport& report, OGRCoordinateTransformation* to_scene);
  OGRCoordinateTransformation* to_scene() const { return to_scene_; }
  const std::string& input_path() const { return scene_.report.inputs.back().path; }

  // Checks `mesh` and moves what is sound into the scene, relative to the origin: triangles with an
  // index out of range, a non-finite corner or no area (in the scene's float coordinates) are
  // dropped, a mesh left without triangles is skipped, unused vertices go. `in_scene_crs`: the
  // vertices are already in the scene's CRS (the reader transformed them).
  void add(SourceMesh&& mesh, bool in_scene_crs = false);
  // An object the reader made no mesh of (no geometry at the chosen LoD, say): counted as skipped,
  // named in the input's warning for `why`.
  void skip(const std::string& object, const std::string& why);
  // Triangles of `object` that were not kept, counted as dropped.
  void drop_triangles(std::int64_t count, const std::string& why, const std::string& object);
  // Polygons of `object` that made no triangle (no area, rings that index no vertex), counted.
  void drop_surfaces(std::int64_t count, const std::string& why, const std::string& object);
  void warn(const std::string& line);
  // Writes the input's grouped warnings.
  void end_input();

  // Ground for footprints: DSM inputs register theirs; lowest_ground asks them in order.
  void add_ground(GroundSampler sampler) { grounds_.push_back(std::move(sampler)); }
  bool has_ground() const { return !grounds_.empty(); }
  // The first ground source's lowest height along `points` (scene CRS); NaN where none covers them.
  double lowest_ground(const std::vector<Vec3d>& points) const;

 private:
  struct Tally {
    std::int64_t count = 0;
    std::int64_t objects = 0;           // distinct objects counted (in a row)
    std::vector<std::string> examples;  // the first few of them
  };
  Scene& scene_;
  OGRCoordinateTransformation* to_scene_ = nullptr;
  void tally(std::map<std::string, Tally>& tallies, std::int64_t count, const std::string& why,
             const std::string& object);
  std::map<std::string, Tally> skipped_, dropped_, surfaces_;  // by reason
  std::vector<GroundSampler> grounds_;
};

}  // namespace skyview
