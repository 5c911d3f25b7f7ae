#pragma once
// What `skyview horizon` and `skyview svf` share: the input, the horizon method and its
// parameters, and progress while they run.
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "command.h"
#include "skyview/horizon/horizon_engine.h"
#include "skyview/raster/raster_io.h"
#include "skyview/raster/terrain_reader.h"
#include "skyview/sky_view/accuracy_choice.h"
#include "skyview/sky_view/horizon_request.h"
#include "skyview/sky_view/sky_view.h"
#include "tiled_job.h"

namespace skyview::cli {

struct HorizonJobOptions {
  std::string input, output;
  int band = 1;
  double z_scale = 0.0;          // 0: from the raster (height_unit.h)
  std::string s_srs;             // the input's CRS where it states none (or a wrong one)
  std::string method = "sweep";  // exact and the fastest for a given error (docs/benchmarks.md)
  // The option naming the horizon method: --method, or --horizon-method where a command's own
  // --method chooses something else (skyview exposure's fast or exact).
  std::string method_option = "--method";
  std::string edge = "open";
  double max_error = -1.0;  // >= 0: choose method and parameters for this p99 svf error
  // Where sector 0 points (AzimuthOrigin): each command sets its default before its options.
  std::string azimuth_origin = "north";
  std::string azimuths = "uniform";  // AzimuthSpacing
  HorizonParams params;
  OutputOptions out;
  const CLI::App* app = nullptr;  // to tell options given from defaults (set by add_horizon_job_options)
};

void add_horizon_job_options(CLI::App& app, HorizonJobOptions& o);

// The input read and the engine set up (HorizonSetup: engine, edge, choice, sectors, metadata).
// A tiled run (tiles.tiled) reads its input by windows through `reader`; then `terrain` is only a
// window about the raster's centre, for the checks that need the raster (fit_horizon).
struct HorizonJob : HorizonSetup {
  Terrain terrain;
  bool quiet = false;
  TilePlan tiles;
  std::shared_ptr<TerrainReader> reader;
  // A tiled run at unlimited radius: the horizons beyond the halo (far_field_job.h), and its width.
  std::shared_ptr<const FarHorizons> far_field;
  double far_halo_m = 0;
  // The raster's size, whole or tiled.
  int width() const { return reader ? reader->width() : terrain.width(); }
  int height() const { return reader ? reader->height() : terrain.height(); }
  const GeoReference& georef() const { return reader ? reader->georef() : terrain.georef; }
};

// The options as the library states them, with those given on the command line marked.
HorizonRequest horizon_request(const HorizonJobOptions& o);

// Reads the input, builds the engine and records the run's parameters; computes nothing yet.
// `more_outputs` (a preview) are refused with the output where they would replace an input. With
// `tiling` (svf, horizon, exposure) the run may go by tiles (HorizonJob::tiles), and the input is then only
// scanned, not read whole.
HorizonJob prepare_horizon_job(const HorizonJobOptions& o, const std::string& command,
                               const std::vector<std::string>& more_outputs = {}, const TileRequest* tiling = nullptr);

// Runs with another of --max-error's choices from now on: its engine and its metadata.
void use_choice(HorizonJob& job, const AccuracyChoice& choice, double max_error);

// Runs `work` with progress over the job's cells on stderr (unless the job is quiet).
void with_progress(const HorizonJob& job, const std::function<void(ProgressCounter&)>& work);

}  // namespace skyview::cli
