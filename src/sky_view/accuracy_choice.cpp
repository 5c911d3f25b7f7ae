#include "skyview/sky_view/accuracy_choice.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "skyview/core/error.h"

namespace skyview {

const std::vector<CalibrationEntry>& calibration_table() {
  // Measured by `skyview bench` against the continuous svf (exact horizons in 1024 sectors at 1000
  // random cells of each raster); see docs/benchmarks.md.
  static const std::vector<CalibrationEntry> table = [] {
    std::vector<CalibrationEntry> measured = {
#include "accuracy_calibration.inc"
    };
    // More samples (exact near steps) along the same directions never make a run less accurate, so
    // an entry measured below one with more of them is 1000 cells' noise: a choice that trusted it
    // ran 128 directions at 16 near steps (0.0036) after 32 (0.0038) had failed, and failed again.
    // Each entry takes the worst p99 of itself and every entry with more samples.
    std::vector<CalibrationEntry> table = measured;
    for (CalibrationEntry& e : table) {
      for (const CalibrationEntry& m : measured) {
        if (m.method == e.method && m.directions == e.directions && m.far_lines == e.far_lines &&
            m.spacing == e.spacing && m.samples > e.samples)
          e.worst_p99 = std::max(e.worst_p99, m.worst_p99);
      }
    }
    return table;
  }();
  return table;
}

namespace {

AccuracyChoice choice_of(const CalibrationEntry& e, const HorizonParams& base) {
  AccuracyChoice c;
  c.method = e.method;
  c.entry = e;
  c.params = base;
  c.params.directions = e.directions;
  c.params.samples = e.samples;
  if (e.far_lines > 0) c.params.far_lines = e.far_lines;
  c.params.spacing = e.spacing;
  c.params.radius = 0.0;  // each method's calibrated default
  return c;
}

// Among the entries `admits`: the cheapest whose p99 is within `target`, and the most accurate.
struct Pick {
  const CalibrationEntry* cheapest = nullptr;
  const CalibrationEntry* most_accurate = nullptr;
};
template <class Admits>
Pick pick(double target, Admits admits) {
  Pick p;
  for (const auto& e : calibration_table()) {
    if (!admits(e)) continue;
    if (!p.most_accurate || e.worst_p99 < p.most_accurate->worst_p99) p.most_accurate = &e;
    if (e.worst_p99 <= target && (!p.cheapest || e.ns_per_cell < p.cheapest->ns_per_cell)) p.cheapest = &e;
  }
  return p;
}

}  // namespace

AccuracyChoice choose_for_max_error(double max_error, const HorizonParams& base) {
  if (!(max_error > 0.0) || max_error > 1.0) throw UsageError("--max-error must be above 0 and at most 1");
  const auto [best, most_accurate] = pick(max_error, [](const CalibrationEntry&) { return true; });
  if (!best) {
    char msg[256];
    std::snprintf(msg, sizeof msg,
                  "no calibrated method reaches a 99th-percentile svf error of %g; the best is %s with %d directions "
                  "(%.4f)",
                  max_error, most_accurate->method.c_str(), most_accurate->directions, most_accurate->worst_p99);
    throw Error(msg);
  }
  return choice_of(*best, base);
}

std::optional<AccuracyChoice> choose_after_measurement(double max_error, const CalibrationEntry& tried,
                                                       const MeasuredError& measured, const HorizonParams& base) {
  if (!(measured.bound > max_error)) return std::nullopt;
  // The raster is harder than the calibration rasters by measured / tried.worst_p99; assume the
  // same factor for every configuration (errors of one method scale together from raster to raster).
  const double target = tried.worst_p99 > 0.0 ? max_error * tried.worst_p99 / measured.bound : 0.0;
  // What the parts ask of the next run (no demand where a part is unknown).
  const bool more_directions = measured.sector_p99 > 0.5 * max_error;
  const bool better_rays = measured.method_p99 > 0.5 * max_error;
  const bool split = !std::isnan(measured.sector_p99) && !std::isnan(measured.method_p99);
  // Pass 0: what the parts ask for; 1: giving up nothing of tried's; 2: the totals alone (each
  // pass only where the one before it found no entry).
  auto admits = [&](const CalibrationEntry& e, int pass) {
    if (pass == 2) return true;
    if (e.method != tried.method || e.directions < tried.directions || e.samples < tried.samples ||
        e.far_lines < tried.far_lines)
      return false;
    if (pass == 1) return true;
    if (more_directions && e.directions == tried.directions) return false;
    if (better_rays && e.samples == tried.samples && e.far_lines == tried.far_lines) return false;
    return true;
  };
  for (int pass = split ? 0 : 2; pass <= 2; ++pass) {
    const Pick p =
        pick(target, [&](const CalibrationEntry& e) { return e.worst_p99 < tried.worst_p99 && admits(e, pass); });
    if (const CalibrationEntry* best = p.cheapest ? p.cheapest : p.most_accurate) return choice_of(*best, base);
  }
  return std::nullopt;
}

std::optional<AccuracyChoice> choose_after_measurement(double max_error, const CalibrationEntry& tried, double measured,
                                                       const HorizonParams& base) {
  MeasuredError m;
  m.bound = measured;
  return choose_after_measurement(max_error, tried, m, base);
}

}  // namespace skyview
