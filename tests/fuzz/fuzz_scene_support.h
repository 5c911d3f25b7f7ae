#pragma once
// What the scene fuzz targets share: an opened input driven through a scene assembly, as load_scene
// drives it, so that every reader's whole path runs.
#include "scene/scene_input.h"

namespace skyview::fuzz {

inline void add_to_scene(SceneInput& input) {
  Scene scene;
  SceneAssembly assembly(scene);
  assembly.begin_input({"fuzz", input.format(), input.declared_crs()}, nullptr);
  input.add_to(assembly);
  assembly.end_input();
  (void)input.extent();
}

}  // namespace skyview::fuzz
