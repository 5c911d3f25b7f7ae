#pragma once
// "Ask for an accuracy, not for knobs": the cheapest calibrated method and parameters whose
// 99th-percentile absolute svf error stayed below the request on every calibration raster. The
// error is against the continuous svf (exact horizons in 1024 sectors), not against a reference of
// as few sectors as the run: 64 sectors alone are about 0.01 off it at p99 in cities, so a request
// below that buys directions as well as exactness along each ray. The table comes from `skyview
// bench` runs (docs/benchmarks.md says on which rasters).
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "skyview/horizon/horizon_engine.h"

namespace skyview {

struct CalibrationEntry {
  std::string method;
  int directions = 16;
  int samples = 16;
  int far_lines = 0;       // sweep: lines whose hulls a cell asks (1 or 2); 0 for other methods
  double worst_p99 = 0;    // worst 99th-percentile |svf - continuous svf| over the calibration rasters, and
                           // over the entries with more samples (calibration_table)
  double ns_per_cell = 0;  // median cost on 2 cores, for ordering
  AzimuthSpacing spacing = AzimuthSpacing::uniform;  // grid_lines: the sweep's 16 exact directions
};

const std::vector<CalibrationEntry>& calibration_table();

struct AccuracyChoice {
  std::string method;
  HorizonParams params;
  CalibrationEntry entry;
};

// Throws skyview::Error when no calibrated configuration reaches `max_error`.
AccuracyChoice choose_for_max_error(double max_error, const HorizonParams& base);

// What the svf check measured of a run (SvfCheck): the bound held to the request and, where the
// check's sectors are the run's own, the error's two parts.
struct MeasuredError {
  double bound = 0;  // 95% bound of the p99 against the near-continuous svf
  // p99 against exact horizons in the run's own sectors: what the method's rays miss.
  double method_p99 = std::numeric_limits<double>::quiet_NaN();
  // p99 of those sectors' exact svf against four times as many: what the sectors miss.
  double sector_p99 = std::numeric_limits<double>::quiet_NaN();
};

// After a run with `tried` measured above `max_error` on the raster itself: the cheapest
// configuration whose calibrated p99, scaled by measured / tried's, is within the request, else
// the most accurate one; nullopt when none is more accurate than `tried` or the run already met
// the request. Where the error's parts are known, the choice gives up none of tried's directions,
// near steps or far lines, and adds directions where the sectors alone take over half the request,
// near steps or a far line where the method's rays do; where no calibrated entry does that, one
// that gives up nothing; where none does either, the totals alone decide. (The calibration's totals
// cannot tell which part a raster is hard on: near steps set the error on a 100² city of 8-18 m
// streets, directions on the calibration rasters.)
std::optional<AccuracyChoice> choose_after_measurement(double max_error, const CalibrationEntry& tried,
                                                       const MeasuredError& measured, const HorizonParams& base);
// The same from the bound alone.
std::optional<AccuracyChoice> choose_after_measurement(double max_error, const CalibrationEntry& tried, double measured,
                                                       const HorizonParams& base);

}  // namespace skyview
