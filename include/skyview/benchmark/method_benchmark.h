#pragma once
// Speed against error: runs horizon methods over a grid of their parameters, times them and
// compares their svf and sky visibility with the ray-cast reference. `skyview bench` writes
// the results as JSON, a markdown table and a time-against-error plot with the Pareto front.
#include <nlohmann/json.hpp>

#include <functional>
#include <memory>

#include <string>
#include <vector>

#include "skyview/sky_view/error_stats.h"
#include "skyview/horizon/horizon_engine.h"
#include "skyview/sky_view/sky_view.h"
#include "skyview/sky_view/svf_check.h"

namespace skyview {

struct BenchConfig {
  std::string method;
  HorizonParams params;
  std::string label() const;
};

struct BenchResult {
  BenchConfig config;
  double seconds = 0;  // median wall time: horizons + products
  double cell_dirs_per_second = 0;
  double radius = 0;  // the engine's search radius in metres, infinite where unlimited
  ErrorStats svf, sky_visibility;
  // svf against the near-continuous svf of exact horizons in 1024 sectors at the reference's
  // sample of cells (BenchReference::continuous): the 64-sector reference leaves its own sector
  // error out, about 0.01 at p99 in cities.
  ErrorStats svf_continuous;
  bool pareto = false;  // no other result is both faster and more accurate (judged_p99)
  // The error that the Pareto front and the plot judge by: against the continuous svf where the
  // bench measured it (what --max-error is calibrated on; the 64-sector reference would rank 128 and
  // 256 directions below 64), else against the ray cast.
  bool has_continuous() const { return svf_continuous.cells > 0; }
  double judged_p99() const { return has_continuous() ? svf_continuous.p99 : svf.p99; }
};

struct BenchReference {
  SkyViewProducts products;
  double seconds = 0;
  int directions = 0;
  AzimuthOrigin azimuth_origin = AzimuthOrigin::north;  // of the reference and of every configuration
  std::shared_ptr<const SvfCheck> continuous;           // 1000 random cells at 256 and 1024 sectors
  // A configuration with more directions than the reference is judged against a coarser one: the
  // reference's own sector error counts against it. (With as many, the two share their azimuths and
  // the difference is the method's own error, which is what those rows are read for.)
  bool limits(const BenchConfig& c) const { return c.params.directions > directions; }
};

// The default grid: sampled (directions x samples), march (directions), sweep (directions 8-256 x
// exact near steps 8-128 x one or two far lines).
std::vector<BenchConfig> default_bench_grid(const std::vector<std::string>& methods);

// The ray cast at `directions` over every cell, and the svf check's exact horizons at 1000 random
// cells in 1024 sectors; both with their first sector at `origin`, which the configurations run must share.
BenchReference compute_reference(const Terrain& terrain, int directions, AzimuthOrigin origin = AzimuthOrigin::north);

constexpr int kBenchContinuousCells = 1000;
constexpr int kBenchContinuousSectors = 1024;

// A configuration that cannot run on the raster (a 500 m radius that puts every sample of the
// sampled method beyond a raster 3 m across), and why.
struct BenchSkipped {
  std::string label, why;
};

// Runs every config `repeats` times, in rounds over all of them (median time); `on_result` is called
// for each config as the last round finishes it. A config whose engine refuses the raster is left
// out of the results and, when `skipped` is given, listed there; otherwise its error is thrown.
std::vector<BenchResult> run_bench(const Terrain& terrain, const std::vector<BenchConfig>& configs,
                                   const BenchReference& reference, int repeats,
                                   const std::function<void(const BenchResult&)>& on_result = {},
                                   std::vector<BenchSkipped>* skipped = nullptr);

void mark_pareto_front(std::vector<BenchResult>& results);
nlohmann::json bench_to_json(const std::string& raster, const BenchReference& ref, const std::vector<BenchResult>& r);
std::string bench_to_markdown(const std::string& raster, const BenchReference& ref, const std::vector<BenchResult>& r);
// Log-log plot of time against p99 svf error (judged_p99), one colour per method, the Pareto front joined;
// written as write_output_file writes (refused if `png_path` exists and !overwrite).
void plot_bench(const std::string& png_path, const std::string& title, const std::vector<BenchResult>& results,
                bool overwrite);

}  // namespace skyview
