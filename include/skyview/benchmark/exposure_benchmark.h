#pragma once
// Speed against error of skyview exposure: settings of the fast method (horizon method and
// directions, the sampler's reads) timed and judged by the exact method with many directions, by
// the relative error of each cell's annual total, over all cells and apart on roofs, streets,
// slopes facing north and wall feet. `skyview bench --exposure` writes the results as JSON, a
// markdown table and a time-against-error plot (docs/benchmarks/exposure.md).
#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

#include "skyview/exposure/exposure.h"
#include "skyview/sky_view/error_stats.h"

namespace skyview {

struct ExposureBenchConfig {
  std::string label, series;  // "sweep d=16 area"; the plot's series
  ExposureMethod method = ExposureMethod::fast;
  std::string horizon_method = "sweep";
  HorizonParams params;
  SamplerOptions sampler;
};

// The fast method with the sweep at 8-64 directions and both reads, the paper's settings (its
// N_dir x (S_dir + S_dir) samples as the sampled method, with mip-map reads), and the exact method
// at 16 and 32 directions for its cost.
std::vector<ExposureBenchConfig> default_exposure_bench_grid();

// What a cell is, for errors by kind of surface: cells beside (8-neighbourhood) one 2.5 m higher
// and within 0.5 m of their lowest neighbour are wall feet (their Horn slope leans on the wall);
// otherwise level cells (slope under 10°) with something 2.5 m higher within 10 m are streets,
// those standing 2.5 m above the lowest within 10 m roofs; slopes of 10-45° whose downslope
// azimuth lies within 45° of north face north.
enum class CellKind : unsigned char { other = 0, roof, street, north_slope, wall_foot };
Grid<unsigned char> classify_cells(const Terrain& terrain);
const char* cell_kind_name(CellKind kind);  // "roofs", "streets", "north slopes", "wall feet"

struct ExposureBenchReference {
  ExposureBands bands;  // the exact method
  double seconds = 0;
  int directions = 0;
  Grid<unsigned char> kinds;  // classify_cells
  // Cells judged: where the exact total is above this share of the unobstructed global horizontal
  // (relative errors of nearly nothing say little).
  double floor_share = 0.01;
};

ExposureBenchReference exposure_bench_reference(const Terrain& terrain, const ExposureSky& sky, int directions);

struct ExposureBenchResult {
  ExposureBenchConfig config;
  double seconds = 0;  // median wall time of compute_exposure (horizons and sampling; the map is shared)
  // Relative error of the total, value / exact − 1: over all judged cells, then by CellKind.
  ErrorStats all, by_kind[5];
  bool pareto = false;
};

// Runs every config `repeats` times in rounds (median time); `on_result` as each is done.
std::vector<ExposureBenchResult> run_exposure_bench(
    const Terrain& terrain, const ExposureSky& sky, const std::vector<ExposureBenchConfig>& configs,
    const ExposureBenchReference& reference, int repeats,
    const std::function<void(const ExposureBenchResult&)>& on_result = {});

nlohmann::json exposure_bench_to_json(const std::string& raster, const ExposureBenchReference& reference,
                                      const std::vector<ExposureBenchResult>& results);
std::string exposure_bench_to_markdown(const std::string& raster, const ExposureBenchReference& reference,
                                       const std::vector<ExposureBenchResult>& results);
// Time against p99 relative error of the total, one colour per series, the Pareto front joined.
void plot_exposure_bench(const std::string& png_path, const std::string& title,
                         const std::vector<ExposureBenchResult>& results, bool overwrite);

}  // namespace skyview
