#include "skyview/sky_view/error_stats.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace skyview {

ErrorStats compare_to_reference(const Grid<float>& value, const Grid<float>& reference, double threshold) {
  std::vector<double> abs_err;
  abs_err.reserve(value.size());
  ErrorStats e;
  e.threshold = threshold;
  double sum2 = 0, sum = 0;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const double v = value.values()[i], r = reference.values()[i];
    if (std::isnan(v) || std::isnan(r)) continue;
    const double d = v - r;
    sum += d;
    sum2 += d * d;
    abs_err.push_back(std::abs(d));
    e.share_above += std::abs(d) > threshold;
  }
  e.cells = static_cast<std::int64_t>(abs_err.size());
  if (abs_err.empty()) return e;
  const double n = static_cast<double>(abs_err.size());
  e.rmse = std::sqrt(sum2 / n);
  e.bias = sum / n;
  e.share_above /= n;
  const std::size_t k = std::min(abs_err.size() - 1, static_cast<std::size_t>(std::ceil(0.99 * n)) - 1);
  std::nth_element(abs_err.begin(), abs_err.begin() + static_cast<std::ptrdiff_t>(k), abs_err.end());
  e.p99 = abs_err[k];
  e.max_abs = *std::max_element(abs_err.begin(), abs_err.end());
  return e;
}

}  // namespace skyview
