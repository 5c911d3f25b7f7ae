// load_scene: the one entry point of the scene readers. It tells each input's format (by content,
// then by what GDAL and Assimp open), chooses the scene's CRS and origin, and hands every input its
// transform into them.
#include <gdal_priv.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string_view>

#include "scene/scene_crs.h"
#include "scene/scene_input.h"
#include "skyview/core/error.h"
#include "skyview/core/lowercase.h"
#include "skyview/core/number_text.h"
#include "skyview/raster/raster_io.h"
#include "skyview/scene/scene.h"

namespace skyview {
namespace {

// The text after a UTF-8 byte order mark and white space.
std::string_view content_start(std::string_view s) {
  if (s.substr(0, 3) == "\xEF\xBB\xBF") s.remove_prefix(3);
  const std::size_t first = s.find_first_not_of(" \t\r\n");
  return first == std::string_view::npos ? std::string_view() : s.substr(first);
}

bool file_contains(const std::string& path, std::string_view needle) {
  std::ifstream in(path, std::ios::binary);
  std::string carry, block(1 << 20, '\0');
  while (in) {
    in.read(block.data(), static_cast<std::streamsize>(block.size()));
    const std::string window = carry + block.substr(0, static_cast<std::size_t>(in.gcount()));
    if (window.find(needle) != std::string::npos) return true;
    carry = window.size() >= needle.size() ? window.substr(window.size() - needle.size()) : window;
  }
  return false;
}

bool is_cityjson(const std::string& path, std::string_view start) {
  if (start.empty() || start.front() != '{') return false;
  if (start.find("CityJSON") != std::string_view::npos || start.find("\"CityObjects\"") != std::string_view::npos) {
    return true;
  }
  // Keys come in any order: "type": "CityJSON" may follow megabytes of vertices.
  const std::string ext = lowercase_extension(path);
  return (ext == ".json" || ext == ".jsonl" || ext == ".cityjson") && file_contains(path, "\"CityJSON");
}

std::unique_ptr<SceneInput> open_input(const std::string& path, const SceneLoadOptions& options) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw Error("cannot open '" + path + "': no such file");
  const std::string head = std::filesystem::is_regular_file(path, ec) ? file_start(path, 1 << 16) : "";
  if (std::filesystem::is_regular_file(path, ec) && head.empty() && std::filesystem::file_size(path, ec) == 0) {
    throw Error("'" + path + "' is empty");
  }
  const std::string_view start = content_start(head);
  if (is_cityjson(path, start)) return open_cityjson(path, options);
  if (!start.empty() && start.front() == '<' && start.find("CityModel") != std::string_view::npos) {
    return open_citygml(path, head, options);
  }
  // GDAL next: rasters are DSMs, vector layers footprints.
  init_gdal();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_VECTOR | GDAL_OF_READONLY));
  CPLPopErrorHandler();
  const bool raster = ds && ds->GetRasterCount() > 0, vector = ds && ds->GetLayerCount() > 0;
  ds.reset();
  if (raster) return open_dsm(path, options);
  if (vector) return open_footprints(path, options);
  if (mesh_format_known(path)) return open_mesh_file(path, options);
  throw Error("cannot tell what '" + path +
              "' is: not CityJSON, CityGML, a GDAL raster or vector layer, nor a mesh format Assimp reads");
}

}  // namespace

Scene load_scene(const std::vector<std::string>& inputs, const SceneLoadOptions& options) {
  if (inputs.empty()) {
    throw Error("no input: give DSM rasters, footprint layers, CityGML, CityJSON or mesh files");
  }
  std::vector<std::unique_ptr<SceneInput>> opened;
  for (const std::string& path : inputs) opened.push_back(open_input(path, options));

  // Each input's CRS: its own, else --s_srs; the scene's: --t_srs, else the first input's.
  const std::size_t n = inputs.size();
  std::vector<std::string> crs_text(n);
  std::vector<std::optional<OGRSpatialReference>> crs(n);
  bool s_srs_used = false;
  for (std::size_t i = 0; i < n; ++i) {
    crs_text[i] = opened[i]->declared_crs();
    if (crs_text[i].empty() && !options.s_srs.empty()) {
      crs_text[i] = options.s_srs;
      s_srs_used = true;
    }
    if (!crs_text[i].empty()) {
      crs[i] = scene_crs(crs_text[i], crs_text[i] == options.s_srs ? "--s_srs" : "'" + inputs[i] + "'");
    }
  }
  std::optional<OGRSpatialReference> target;
  std::string target_what;
  if (!options.t_srs.empty()) {
    target = scene_crs(options.t_srs, "--t_srs");
    target_what = "--t_srs";
  } else {
    for (std::size_t i = 0; i < n && !target; ++i) {
      if (crs[i]) target = *crs[i], target_what = "'" + inputs[i] + "'";
    }
  }
  Scene scene;
  if (target) {
    for (std::size_t i = 0; i < n; ++i) {
      if (!crs[i]) {
        throw Error("'" + inputs[i] + "' carries no CRS, and the scene's is " +
                    std::string(target->GetName() ? target->GetName() : "another") + " (from " + target_what +
                    "): give --s_srs, the CRS of its coordinates");
      }
    }
    double lon = std::numeric_limits<double>::quiet_NaN(), lat = lon;
    if (target->IsGeographic()) {  // where the data lie, for the UTM zone the message suggests
      for (std::size_t i = 0; i < n && std::isnan(lon); ++i) {
        const auto e = opened[i]->extent();
        if (!e) continue;
        double x = 0.5 * ((*e)[0][0] + (*e)[1][0]), y = 0.5 * ((*e)[0][1] + (*e)[1][1]);
        TransformPtr t(OGRCreateCoordinateTransformation(&*crs[i], &*target));
        if (!crs[i]->IsSame(&*target) && (!t || !t->Transform(1, &x, &y))) continue;
        lon = x, lat = y;
      }
    }
    require_projected_metres(*target, target_what, lon, lat);
    char* wkt = nullptr;
    target->exportToWkt(&wkt);
    scene.crs_wkt = wkt ? wkt : "";
    CPLFree(wkt);
  }
  std::vector<TransformPtr> to_scene(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (target) to_scene[i] = scene_transform(*crs[i], *target, "'" + inputs[i] + "'");
  }
  if (!options.s_srs.empty() && !s_srs_used) {
    scene.report.warnings.push_back("--s_srs is not used: every input states its own CRS");
  }

  // The origin: the first input's centre, in whole metres (heights stay as they are).
  for (std::size_t i = 0; i < n; ++i) {
    const auto e = opened[i]->extent();
    if (!e) continue;
    double c[3] = {0.5 * ((*e)[0][0] + (*e)[1][0]), 0.5 * ((*e)[0][1] + (*e)[1][1]), 0.0};
    if (to_scene[i] && !to_scene[i]->Transform(1, &c[0], &c[1], &c[2])) continue;
    if (!std::isfinite(c[0]) || !std::isfinite(c[1])) continue;
    scene.origin = {std::round(c[0]) + 0.0, std::round(c[1]) + 0.0, 0.0};  // (+ 0.0: no -0)
    break;
  }

  // Rasters first: footprints stand on them.
  SceneAssembly assembly(scene);
  for (const bool ground : {true, false}) {
    for (std::size_t i = 0; i < n; ++i) {
      if (!opened[i] || opened[i]->is_ground() != ground) continue;
      SceneInputReport report;
      report.path = inputs[i];
      report.format = opened[i]->format();
      report.crs = crs_display_name(crs_text[i]);
      assembly.begin_input(report, to_scene[i].get());
      opened[i]->add_to(assembly);
      assembly.end_input();
      opened[i].reset();  // its memory, before the next is read
    }
  }
  // Float vertices step by 1/16 mm at 1 km from the origin, by 6 cm at 1000 km: inputs far apart
  // (cities in different countries) lose their small triangles.
  const auto b = scene.bounds();
  double far = 0;
  for (int k = 0; k < 3; ++k) far = std::max({far, std::abs(double(b[0][k])), std::abs(double(b[1][k]))});
  if (b[0][0] <= b[1][0] && far > 1e5) {
    scene.report.warnings.push_back("the scene reaches " + std::to_string(static_cast<long long>(far / 1000)) +
                                    " km from its origin, where its float coordinates step by " +
                                    number_text(std::ldexp(1.0, std::ilogb(far) - 23)) +
                                    " m: inputs that far apart are better loaded as scenes of their own");
  }
  if (scene.triangle_count() == 0) {
    std::string why = scene.report.warnings.empty() ? "" : " (" + scene.report.warnings.front() + ")";
    throw Error("the inputs hold no triangles" + why);
  }
  return scene;
}

}  // namespace skyview
