#include "scene_options.h"

#include <algorithm>
#include <cstdio>

#include "command.h"

namespace skyview::cli {
namespace {

bool any_format(const Scene& s, const std::string& prefix) {
  return std::any_of(s.report.inputs.begin(), s.report.inputs.end(),
                     [&](const SceneInputReport& i) { return i.format.rfind(prefix, 0) == 0; });
}

}  // namespace

CLI::Option* add_scene_options(CLI::App& app, SceneInputOptions& o, const std::string& up_option) {
  o.up_option = up_option;
  CLI::Option* inputs =
      app.add_option("inputs", o.inputs,
                     "DSM rasters (any GDAL raster), footprint layers (any OGR polygon layer), CityGML, CityJSON, "
                     "mesh files (OBJ, PLY, glTF/GLB, STL, ...)")
          ->required();
  app.add_option("--s_srs", o.load.s_srs,
                 "CRS of inputs that carry none (mesh files, CityJSON without referenceSystem, CityGML without "
                 "srsName)");
  app.add_option("--t_srs", o.load.t_srs,
                 "The scene's CRS, projected in metres (default: the first input's that has one)");
  app.add_option("--lod", o.load.lod,
                 "CityGML and CityJSON: take each object's highest level of detail not above this (2, 2.2, 1); "
                 "default: each object's highest");
  app.add_option("--height-field", o.load.height_field,
                 "Footprints: the buildings' height attribute (above the lowest ground along the outline: a flat "
                 "top)");
  app.add_option("--base-field", o.load.base_field, "Footprints: absolute base height attribute (the prism's bottom)");
  app.add_flag("--absolute-heights", o.load.absolute_heights,
               "Footprints: the height field is absolute, not above the ground");
  app.add_option("--footprint-z-scale", o.load.footprint_z_scale,
                 "Footprints: metres per unit of --height-field and --base-field (0.3048 for feet); default: "
                 "metres, refused where the layer's CRS is in another unit")
      ->check(positive_number());
  app.add_option("--z-scale", o.load.z_scale,
                 "DSM rasters: metres per height unit (0.3048 for feet); default: each raster's band unit or "
                 "vertical CRS, else metres")
      ->check(positive_number());
  app.add_flag("--no-skirts", o.no_skirts,
               "DSM rasters: leave out the skirts the ray cast hangs from open edges (ten cells deep)");
  app.add_option(up_option, o.load.up_axis,
                 "Mesh files: the file's up axis, y (turned to z: x east, -z north) or z (as stored); default: y "
                 "for glTF, COLLADA and FBX, z for the others")
      ->check(CLI::IsMember({"y", "z"}));
  return inputs;
}

Scene load_scene_inputs(const CLI::App& app, SceneInputOptions& o) {
  o.load.dsm_skirts = !o.no_skirts;
  Scene s = load_scene(o.inputs, o.load);
  // Options no input used would leave a batch job answering another question than it asked.
  const bool footprints = any_format(s, "footprints"), rasters = any_format(s, "raster"),
             meshes = any_format(s, "mesh"), city = any_format(s, "City");
  for (const char* option : {"--height-field", "--base-field", "--absolute-heights", "--footprint-z-scale"}) {
    refuse_unused(app, option, footprints, "footprint layers, and no input is one");
  }
  refuse_unused(app, "--z-scale", rasters, "DSM rasters, and no input is one");
  refuse_unused(app, "--no-skirts", rasters, "DSM rasters, and no input is one");
  refuse_unused(app, o.up_option, meshes, "mesh files, and no input is one");
  refuse_unused(app, "--lod", city, "CityGML and CityJSON inputs, and no input is one");
  const bool s_srs_used = std::none_of(s.report.warnings.begin(), s.report.warnings.end(),
                                       [](const std::string& w) { return w.rfind("--s_srs is not used", 0) == 0; });
  refuse_unused(app, "--s_srs", s_srs_used, "inputs without a CRS, and every input states its own");
  for (const std::string& w : s.report.warnings) std::fprintf(stderr, "Warning: %s\n", w.c_str());
  return s;
}

}  // namespace skyview::cli
