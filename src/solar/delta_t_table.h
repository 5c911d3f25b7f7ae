#pragma once
// Observed Delta T samples (delta_t_table.cpp), on the first day of the given month.

namespace skyview::detail {

struct DeltaTSample {
  int year, month;
  double delta_t_s;
};

extern const DeltaTSample kObservedDeltaT[];
extern const int kObservedDeltaTCount;

}  // namespace skyview::detail
