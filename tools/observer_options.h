#pragma once
// What `skyview points` and `skyview fisheye` share: the DSM, the observer's height and the options
// of the point horizons (the march along each observer's own rays, or the ray cast).
#include <map>
#include <string>

#include "command.h"
#include "skyview/horizon/point_horizons.h"
#include "skyview/raster/terrain.h"

namespace skyview::cli {

struct ObserverOptions {
  int band = 1;
  double z_scale = 0.0;
  double height = 1.1;
  std::string method = "march";
  std::string azimuth_origin = "north";
  PointHorizonOptions horizons;
  bool overwrite = false, quiet = false;
  int threads = 0;
};

// -b, --z-scale, --height, --method, --directions (default `directions`), --radius, --curvature,
// --refraction, --azimuth-origin, --overwrite, -q and --threads.
void add_observer_options(CLI::App& app, ObserverOptions& o, int directions);

// The horizon options as given, checked (throws skyview::Error).
PointHorizonOptions observer_horizon_options(const CLI::App& app, const ObserverOptions& o);

// Reads the DSM as every horizon command does (warning on undeclared NaN cells) and fills
// `metadata` with the run's parameters.
Terrain read_observer_terrain(const std::string& path, const ObserverOptions& o,
                              std::map<std::string, std::string>& metadata);

}  // namespace skyview::cli
