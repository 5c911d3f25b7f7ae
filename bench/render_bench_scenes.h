#pragma once
// The scenes the camera-view benchmarks share: 0, the synthetic city (401 x 401 cells of 1 m) written
// to a temporary GeoTIFF named after `bench`; 1, Berlin's LoD2 sample from ../shared. The path, or
// "" where the sample is absent.
#include <cstdlib>
#include <filesystem>
#include <string>

#include "skyview/raster/band_writer.h"
#include "skyview/synthetic/synthetic.h"

namespace skyview {

inline std::string render_bench_scene(int which, const std::string& bench) {
  if (which == 0) {
    const std::string path = (std::filesystem::temp_directory_path() / (bench + "_city.tif")).string();
    GeoReference g = local_grid(401, 401, 1.0);
    WriteOptions wo;
    wo.overwrite = true;
    write_terrain(path, rasterize(synthetic_city(1), 401, 401, g), wo);
    return path;
  }
  // SKYVIEW_SHARED_DIR in the environment overrides the build's (a worktree's ../shared is elsewhere).
  const char* shared = std::getenv("SKYVIEW_SHARED_DIR");
  const std::string path =
      std::string(shared ? shared : SKYVIEW_SHARED_DIR) + "/sample_data/city3d/berlin_sample.citygml";
  return std::filesystem::exists(path) ? path : std::string();
}

}  // namespace skyview
