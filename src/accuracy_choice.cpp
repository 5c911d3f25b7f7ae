#include "skyview/accuracy_choice.h"

#include <algorithm>
#include <cstdio>

#include "skyview/error.h"

namespace skyview {

const std::vector<CalibrationEntry>& calibration_table() {
  // Measured by `skyview bench` against a 64-direction ray cast; see docs/benchmarks.md.
  static const std::vector<CalibrationEntry> table = {
#include "accuracy_calibration.inc"
  };
  return table;
}

AccuracyChoice choose_for_max_error(double max_error, const HorizonParams& base) {
  if (!(max_error > 0.0) || max_error > 1.0) throw Error("--max-error must be above 0 and at most 1");
  const CalibrationEntry* best = nullptr;
  const CalibrationEntry* most_accurate = nullptr;
  for (const auto& e : calibration_table()) {
    if (!most_accurate || e.worst_p99 < most_accurate->worst_p99) most_accurate = &e;
    if (e.worst_p99 <= max_error && (!best || e.ns_per_cell < best->ns_per_cell)) best = &e;
  }
  if (!best) {
    char msg[256];
    std::snprintf(msg, sizeof msg,
                  "no calibrated method reaches a 99th-percentile svf error of %g; the best is %s with %d directions "
                  "(%.4f)",
                  max_error, most_accurate->method.c_str(), most_accurate->directions, most_accurate->worst_p99);
    throw Error(msg);
  }
  AccuracyChoice c;
  c.method = best->method;
  c.entry = *best;
  c.params = base;
  c.params.directions = best->directions;
  c.params.samples = best->samples;
  if (best->far_lines > 0) c.params.far_lines = best->far_lines;
  c.params.radius = 0.0;  // each method's calibrated default
  return c;
}

}  // namespace skyview
