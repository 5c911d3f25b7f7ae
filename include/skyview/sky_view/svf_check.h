#pragma once
// A run's svf error measured on the raster itself, where --max-error's calibration only predicts
// it: the svf of a random sample of cells from exact horizons (the march over every row and column
// crossing of the surface every method reads, to the raster's edge, with the run's curvature),
// integrated over the sectors the calibration's ray-cast reference uses, and the run's svf
// compared with it there.
#include <cstdint>
#include <vector>

#include "skyview/core/grid.h"
#include "skyview/horizon/horizon_engine.h"
#include "skyview/raster/terrain.h"
#include "skyview/sky_view/error_stats.h"

namespace skyview {

// The most sectors a check measures against (it walks four times as many at every checked cell).
constexpr int kSvfCheckMaxDirections = 1024;

struct SvfCheckOptions {
  int cells = 1000;        // cells sampled; every valid cell when the raster has no more
  int directions = 64;     // sectors of the reference (the calibration's)
  double curvature = 0.0;  // c of the drop c d² that the run applied (HorizonEngine::curvature_coefficient)
  AzimuthOrigin azimuth_origin = AzimuthOrigin::north;  // the run's: its sectors are the reference's
  std::uint64_t seed = 1;
};

struct SvfCheckResult {
  ErrorStats error;             // of svf - reference over the sampled cells where svf is valid
  ErrorStats error_fine;        // of svf - the svf at four times the reference's sectors: near the continuous svf
  double p99_upper95 = 0;       // one-sided 95% confidence bound of the raster's p99 (NaN: too few cells)
  double fine_p99_upper95 = 0;  // the same for error_fine: what --max-error is held to
  bool exhaustive = false;      // every valid cell was checked: error.p99 is the raster's own
};

class SvfCheck {
 public:
  // Samples the cells (uniformly among the valid ones, the same for the same raster and seed) and
  // computes their reference svf, and also at four times the sectors, which says how far the
  // reference's own sector integration is from the continuous svf there.
  SvfCheck(const Terrain& terrain, const SvfCheckOptions& options);

  SvfCheckResult measure(const Grid<float>& svf) const;

  const std::vector<CellIndex>& cells() const { return cells_; }
  const std::vector<double>& reference() const { return reference_; }
  const std::vector<double>& fine_reference() const { return fine_reference_; }
  int directions() const { return directions_; }
  int fine_directions() const { return kFinerSectors * directions_; }
  double curvature() const { return curvature_; }
  bool exhaustive() const { return exhaustive_; }
  // 99th percentile of |reference - the same at four times the sectors| over the sampled cells.
  double sector_p99() const { return sector_p99_; }
  double seconds() const { return seconds_; }

 private:
  static constexpr int kFinerSectors = 4;
  std::vector<CellIndex> cells_;
  std::vector<double> reference_, fine_reference_;
  int directions_ = 0;
  double curvature_ = 0;
  bool exhaustive_ = false;
  double sector_p99_ = 0, seconds_ = 0;
};

// The rank (1-based, ascending) of the order statistic of n samples that bounds the population's
// q-quantile from above with the given confidence (the binomial bound), or 0 when n is too small.
std::int64_t quantile_upper_rank(std::int64_t n, double q, double confidence);

}  // namespace skyview
