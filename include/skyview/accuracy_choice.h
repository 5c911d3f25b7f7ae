#pragma once
// "Ask for an accuracy, not for knobs": the cheapest calibrated method and parameters whose
// 99th-percentile absolute svf error stayed below the request on every calibration raster. The
// error is against the continuous svf (exact horizons in 1024 sectors), not against a reference of
// as few sectors as the run: 64 sectors alone are about 0.01 off it at p99 in cities, so a request
// below that buys directions as well as exactness along each ray. The table comes from `skyview
// bench` runs (docs/benchmarks.md says on which rasters).
#include <optional>
#include <string>
#include <vector>

#include "skyview/horizon_engine.h"

namespace skyview {

struct CalibrationEntry {
  std::string method;
  int directions = 16;
  int samples = 16;
  int far_lines = 0;       // sweep: lines whose hulls a cell asks (1 or 2); 0 for other methods
  double worst_p99 = 0;    // worst 99th-percentile |svf - continuous svf| over the calibration rasters, and
                           // over the entries with more samples (calibration_table)
  double ns_per_cell = 0;  // median cost on 2 cores, for ordering
};

const std::vector<CalibrationEntry>& calibration_table();

struct AccuracyChoice {
  std::string method;
  HorizonParams params;
  CalibrationEntry entry;
};

// Throws skyview::Error when no calibrated configuration reaches `max_error`.
AccuracyChoice choose_for_max_error(double max_error, const HorizonParams& base);

// After a run with `tried` measured a p99 of `measured` above `max_error` on the raster itself
// (SvfCheck): the cheapest configuration whose calibrated p99, scaled by measured / tried's, is
// within the request, else the most accurate one; nullopt when none is more accurate than `tried`
// or the run already met the request.
std::optional<AccuracyChoice> choose_after_measurement(double max_error, const CalibrationEntry& tried, double measured,
                                                       const HorizonParams& base);

}  // namespace skyview
