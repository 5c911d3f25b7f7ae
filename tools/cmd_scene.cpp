// skyview scene: loads DSM rasters, footprint layers, CityGML, CityJSON and mesh files into one 3-D
// scene (as skyview render does) and says what it holds; --out writes it as a PLY to look at.
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "command.h"
#include "scene_options.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/raster/raster_io.h"
#include "skyview/scene/scene.h"
#include "skyview/scene/scene_output.h"

namespace skyview::cli {
namespace {

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
    SceneInputOptions scene;
    std::string out;
    bool json = false, overwrite = false, quiet = false;
  };
  auto o = std::make_shared<Options>();
  add_scene_options(app, o->scene);
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
      check_outputs_apart({o->out}, o->scene.inputs);
      check_output_writable(o->out, o->overwrite);
    }
    refuse_unused(app, "--overwrite", !o->out.empty(), "--out");
    const Scene s = load_scene_inputs(app, o->scene);
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
