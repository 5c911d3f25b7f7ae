#pragma once
// What a horizon-using run asks for (method, directions, radius, edges, --max-error ...), checked
// and turned into an engine and the run's metadata. The command line, the Python module and tiled
// runs state their options here, so that all three refuse the same things with the same words.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "skyview/horizon/direction_set.h"
#include "skyview/horizon/horizon_engine.h"
#include "skyview/sky_view/accuracy_choice.h"
#include "skyview/sky_view/sky_view.h"

namespace skyview {

struct HorizonRequest {
  std::string method = "sweep";  // exact and the fastest for a given error (docs/benchmarks.md)
  // The option that names the method in messages: --method, or --horizon-method where a command's
  // own --method chooses something else (skyview exposure's fast or exact).
  std::string method_option = "--method";
  std::string edge = "open";             // open | nodata
  double max_error = -1.0;               // >= 0: choose method and parameters for this p99 svf error
  std::string azimuth_origin = "north";  // north | grid (AzimuthOrigin)
  std::string azimuths = "uniform";      // uniform | grid-lines (AzimuthSpacing)
  HorizonParams params;
  // The options the caller set explicitly, by the command line's long names ("--rays",
  // "--refraction"): an option the run would not use is refused rather than ignored.
  std::set<std::string> given;
  bool was_given(const std::string& option) const { return given.count(option) > 0; }
};

// The engine a request runs with and what its output records.
struct HorizonSetup {
  std::unique_ptr<HorizonEngine> engine;
  EdgeMode edge = EdgeMode::open;
  std::optional<AccuracyChoice> choice;         // --max-error's, when given
  double sector_rotation = 0;                   // of the direction set (radians; direction_set_rotation)
  DirectionSet sectors;                         // its azimuths from sector_rotation, and their weights
  std::map<std::string, std::string> metadata;  // the method's parameters
  std::vector<std::string> method_keys;         // the metadata keys that describe the method
  std::vector<std::string> warnings;            // one line each, for stderr (even under -q)
};

// Throws skyview::Error (the command line's message) for an option the run would not use,
// options that contradict each other, or invalid parameters. Reads nothing: call it before any
// input is read, so that a user fixing one error does not meet an older one next.
HorizonSetup plan_horizon(const HorizonRequest& request);

// The checks that need the raster (a radius reaching no neighbour, --edge nodata blanking every
// cell, curvature auto leaving --refraction unused), and the method's metadata.
void fit_horizon(HorizonSetup& setup, const HorizonRequest& request, const Terrain& terrain);

// "sweep with 64 directions, 16 exact near steps and 1 far line"
std::string describe_choice(const AccuracyChoice& choice);

// Runs with another of --max-error's choices from now on: its engine and its metadata.
void use_choice(HorizonSetup& setup, const AccuracyChoice& choice, double max_error, const Terrain& terrain);

// EDGE_CELLS (and, where any, EDGE_NOTE: what --edge did with them) into the metadata.
void record_edge_cells(HorizonSetup& setup, std::int64_t edge_cells);

// The metadata every horizon product records about its angles and nodata.
std::map<std::string, std::string> horizon_conventions();

}  // namespace skyview
