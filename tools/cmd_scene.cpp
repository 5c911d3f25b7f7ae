// skyview scene: loads DSM rasters, footprint layers, CityGML, CityJSON and mesh files into one 3-D
// scene (as skyview render does) and says what it holds; --out writes it as a PLY to look at.
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "command.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/raster/raster_io.h"
#include "skyview/scene/scene.h"
#include "skyview/scene/scene_output.h"

namespace skyview::cli {
namespace {

bool any_format(const Scene& s, const std::string& prefix) {
  return std::any_of(s.report.inputs.begin(), s.report.inputs.end(),
                     [&](const SceneInputReport& i) { return i.format.rfind(prefix, 0) == 0; });
}

// "1 mesh", "2 meshes".
std::string count(long long n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

void print_summary(const Scene& s, const nlohmann::json& j) {
  const auto meshes = static_cast<long long>(s.meshes.size());
  const auto triangles = static_cast<long long>(s.triangle_count());
  std::printf("Scene: %s, %s\n", count(meshes, "mesh", "meshes").c_str(),
              count(triangles, "triangle", "triangles").c_str());
  std::printf("CRS: %s\n", j["crs"].get<std::string>().c_str());
  std::printf("Origin: %s %s %s (vertices are stored relative to it)\n", number_text(s.origin[0]).c_str(),
              number_text(s.origin[1]).c_str(), number_text(s.origin[2]).c_str());
  const auto& b = j["bounds"];
  std::printf("Bounds: x %.3f to %.3f, y %.3f to %.3f, z %.3f to %.3f\n", b["min"][0].get<double>(),
              b["max"][0].get<double>(), b["min"][1].get<double>(), b["max"][1].get<double>(),
              b["min"][2].get<double>(), b["max"][2].get<double>());
  std::printf("Inputs:\n");
  for (const SceneInputReport& i : s.report.inputs) {
    std::printf("  %s: %s, CRS %s: %s, %s", i.path.c_str(), i.format.c_str(), i.crs.c_str(),
                count(i.meshes, "mesh", "meshes").c_str(), count(i.triangles, "triangle", "triangles").c_str());
    if (i.meshes_skipped + i.surfaces_skipped + i.triangles_skipped > 0) {
      std::printf("; skipped %s, %s, %s", count(i.meshes_skipped, "object", "objects").c_str(),
                  count(i.surfaces_skipped, "surface", "surfaces").c_str(),
                  count(i.triangles_skipped, "triangle", "triangles").c_str());
    }
    std::printf("\n");
  }
  const SceneReport& r = s.report;
  std::printf("Skipped: %s, %s, %s%s\n", count(r.meshes_skipped, "object", "objects").c_str(),
              count(r.surfaces_skipped, "surface", "surfaces").c_str(),
              count(r.triangles_skipped, "triangle", "triangles").c_str(),
              r.meshes_skipped + r.surfaces_skipped + r.triangles_skipped > 0 ? " (the warnings say which)" : "");
}

Runner setup(CLI::App& app) {
  struct Options {
    std::vector<std::string> inputs;
    SceneLoadOptions load;
    std::string out;
    bool json = false, no_skirts = false, overwrite = false, quiet = false;
  };
  auto o = std::make_shared<Options>();
  app.add_option("inputs", o->inputs,
                 "DSM rasters (any GDAL raster), footprint layers (any OGR polygon layer), CityGML, CityJSON, "
                 "mesh files (OBJ, PLY, glTF/GLB, STL, ...)")
      ->required();
  app.add_option("--s_srs", o->load.s_srs,
                 "CRS of inputs that carry none (mesh files, CityJSON without referenceSystem, CityGML without "
                 "srsName)");
  app.add_option("--t_srs", o->load.t_srs,
                 "The scene's CRS, projected in metres (default: the first input's that has one)");
  app.add_option("--lod", o->load.lod,
                 "CityGML and CityJSON: take each object's highest level of detail not above this (2, 2.2, 1); "
                 "default: each object's highest");
  app.add_option("--height-field", o->load.height_field,
                 "Footprints: the buildings' height attribute (above the lowest ground along the outline: a flat "
                 "top)");
  app.add_option("--base-field", o->load.base_field, "Footprints: absolute base height attribute (the prism's bottom)");
  app.add_flag("--absolute-heights", o->load.absolute_heights,
               "Footprints: the height field is absolute, not above the ground");
  app.add_option("--footprint-z-scale", o->load.footprint_z_scale,
                 "Footprints: metres per unit of --height-field and --base-field (0.3048 for feet); default: "
                 "metres, refused where the layer's CRS is in another unit")
      ->check(positive_number());
  app.add_option("--z-scale", o->load.z_scale,
                 "DSM rasters: metres per height unit (0.3048 for feet); default: each raster's band unit or "
                 "vertical CRS, else metres")
      ->check(positive_number());
  app.add_flag("--no-skirts", o->no_skirts,
               "DSM rasters: leave out the skirts the ray cast hangs from open edges (ten cells deep)");
  app.add_option("--up", o->load.up_axis,
                 "Mesh files: the file's up axis, y (turned to z: x east, -z north) or z (as stored); default: y "
                 "for glTF, COLLADA and FBX, z for the others")
      ->check(CLI::IsMember({"y", "z"}));
  app.add_flag("--json", o->json, "Print the summary as JSON on standard output");
  app.add_option("--out", o->out, "Also write the merged scene as a binary PLY (relative to the origin)");
  app.add_flag("--overwrite", o->overwrite, "Replace an existing --out file");
  app.add_flag("-q,--quiet", o->quiet, "Print no text summary (the JSON, warnings and errors still)");
  app.footer(
      "Every input is brought into one projected CRS in metres; vertices are stored relative to an origin (the "
      "first input's centre, in whole metres), z up. Bad objects (no area, NaN vertices, nothing at the chosen "
      "LoD) are skipped and counted in warnings on stderr.");
  return [o, &app] {
    if (!o->out.empty()) {
      require_extension(o->out, {".ply"}, "--out");
      check_outputs_apart({o->out}, o->inputs);
      check_output_writable(o->out, o->overwrite);
    }
    refuse_unused(app, "--overwrite", !o->out.empty(), "--out");
    o->load.dsm_skirts = !o->no_skirts;
    const Scene s = load_scene(o->inputs, o->load);
    // Options no input used would leave a batch job answering another question than it asked.
    const bool footprints = any_format(s, "footprints"), rasters = any_format(s, "raster"),
               meshes = any_format(s, "mesh"), city = any_format(s, "City");
    for (const char* option : {"--height-field", "--base-field", "--absolute-heights", "--footprint-z-scale"}) {
      refuse_unused(app, option, footprints, "footprint layers, and no input is one");
    }
    refuse_unused(app, "--z-scale", rasters, "DSM rasters, and no input is one");
    refuse_unused(app, "--no-skirts", rasters, "DSM rasters, and no input is one");
    refuse_unused(app, "--up", meshes, "mesh files, and no input is one");
    refuse_unused(app, "--lod", city, "CityGML and CityJSON inputs, and no input is one");
    const bool s_srs_used = std::none_of(s.report.warnings.begin(), s.report.warnings.end(),
                                         [](const std::string& w) { return w.rfind("--s_srs is not used", 0) == 0; });
    refuse_unused(app, "--s_srs", s_srs_used, "inputs without a CRS, and every input states its own");
    for (const std::string& w : s.report.warnings) std::fprintf(stderr, "Warning: %s\n", w.c_str());
    const nlohmann::json summary = scene_summary(s);
    if (o->json) {
      std::printf("%s\n", summary.dump(2).c_str());
    } else if (!o->quiet) {
      print_summary(s, summary);
    }
    if (!o->out.empty()) {
      write_scene_ply(s, o->out, o->overwrite);
      if (!o->quiet) {
        std::fprintf(stderr, "Wrote %s: %s, %s\n", o->out.c_str(),
                     count(static_cast<long long>(s.meshes.size()), "mesh", "meshes").c_str(),
                     count(static_cast<long long>(s.triangle_count()), "triangle", "triangles").c_str());
      }
    }
    return 0;
  };
}

const Registration registration("scene",
                                "Load DSMs, footprints, CityGML, CityJSON and meshes into one 3-D scene and "
                                "summarise it (--out scene.ply to look at it)",
                                setup);

}  // namespace
}  // namespace skyview::cli
