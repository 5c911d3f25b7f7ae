// The stretch of a preview's colour ramp (raster_preview.h says the rule).
#include <algorithm>
#include <cmath>
#include <vector>

#include "skyview/preview/raster_preview.h"

namespace skyview {
namespace {

// The q-th percentile (0..100) of `v`, which it reorders; nearest rank.
double percentile(std::vector<float>& v, double q) {
  const auto k = static_cast<std::size_t>(std::lround(q / 100.0 * static_cast<double>(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

std::pair<double, double> preview_range(const Grid<float>& values, const PreviewSpec& spec) {
  if (spec.range) return *spec.range;
  const bool diverging = spec.ramp == ColourRamp::diverging;
  // At most about a million values: the percentiles of a regular sample of a larger raster.
  const std::size_t stride = std::max<std::size_t>(1, values.size() / 1000000);
  std::vector<float> valid;
  valid.reserve(values.size() / stride + 1);
  for (std::size_t i = 0; i < values.size(); i += stride) {
    const float v = values.values()[i];
    if (!std::isnan(v)) valid.push_back(diverging ? std::fabs(v) : v);
  }
  if (valid.empty()) return {0.0, 1.0};
  if (diverging) {
    double m = percentile(valid, kStretchHighPercentile);
    if (!(m > 0.0)) m = 1.0;
    return {-m, m};
  }
  double lo = percentile(valid, kStretchLowPercentile);
  double hi = percentile(valid, kStretchHighPercentile);
  if (!(hi > lo)) {
    // One value (a flat roof, an svf of 1 everywhere): a narrow ramp around it, not a division by zero.
    const double pad = std::max(std::fabs(lo) * 0.01, 1e-6);
    lo -= pad;
    hi += pad;
  }
  return {lo, hi};
}

}  // namespace skyview
