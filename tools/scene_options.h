#pragma once
// The scene inputs and their options, shared by the commands that load a 3-D scene (skyview
// scene, skyview render): the same names, help and checks everywhere.
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "skyview/scene/scene.h"

namespace skyview::cli {

struct SceneInputOptions {
  std::vector<std::string> inputs;
  SceneLoadOptions load;
  bool no_skirts = false;
  std::string up_option = "--up";
};

// Adds the positional `inputs` (required) and --s_srs, --t_srs, --lod, --height-field,
// --base-field, --absolute-heights, --footprint-z-scale, --z-scale, --no-skirts and the mesh files'
// up axis as `up_option` (--up; skyview render, whose --up is the camera's, names it --mesh-up).
CLI::Option* add_scene_options(CLI::App& app, SceneInputOptions& o, const std::string& up_option = "--up");

// Loads the scene; refuses (UsageError) options that no input used and prints the loader's
// warnings on stderr.
Scene load_scene_inputs(const CLI::App& app, SceneInputOptions& o);

}  // namespace skyview::cli
