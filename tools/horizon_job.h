#pragma once
// What `skyview horizon` and `skyview svf` share: the input, the horizon method and its
// parameters, and the run that turns a raster into a HorizonField with progress.
#include <map>
#include <memory>
#include <string>

#include "command.h"
#include "skyview/horizon_engine.h"
#include "skyview/raster_io.h"
#include "skyview/sky_view.h"

namespace skyview::cli {

struct HorizonJobOptions {
  std::string input, output;
  int band = 1;
  double z_scale = 1.0;
  std::string method = "sweep";  // exact and the fastest for a given error (docs/benchmarks.md)
  std::string edge = "open";
  double max_error = 0.0;  // > 0: choose method and parameters for this p99 svf error
  HorizonParams params;
  OutputOptions out;
};

void add_horizon_job_options(CLI::App& app, HorizonJobOptions& o);

struct HorizonJob {
  Terrain terrain;
  std::unique_ptr<HorizonEngine> engine;
  HorizonField field;
  EdgeMode edge = EdgeMode::open;
  std::map<std::string, std::string> metadata;  // run parameters for the output
};

// Reads the input, builds the engine and computes horizons with progress on stderr.
HorizonJob run_horizon_job(const HorizonJobOptions& o, const std::string& command);

}  // namespace skyview::cli
