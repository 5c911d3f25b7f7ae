#pragma once
// How far one raster is from another: the statistics every comparison in skyview reports
// (`skyview bench` against the ray-cast reference, `skyview compare` against any raster).
#include <cstdint>

#include "skyview/core/grid.h"

namespace skyview {

struct ErrorStats {
  double rmse = 0, bias = 0;  // of value - reference
  double p99 = 0;             // 99th percentile of |value - reference| (nearest rank)
  double max_abs = 0;
  double threshold = 0.01;
  double share_above = 0;  // share of cells with |value - reference| > threshold
  std::int64_t cells = 0;  // cells where both are valid
};

// Statistics of (value - reference) over cells where both are valid (not NaN).
ErrorStats compare_to_reference(const Grid<float>& value, const Grid<float>& reference, double threshold = 0.01);

}  // namespace skyview
