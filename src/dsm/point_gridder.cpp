#include "skyview/dsm/point_gridder.h"

#include <algorithm>

#include "skyview/core/error.h"

namespace skyview {

GridStatistic parse_grid_statistic(const std::string& name) {
  if (name == "max") return GridStatistic::max;
  if (name == "mean") return GridStatistic::mean;
  if (name == "min") return GridStatistic::min;
  if (name == "idw") return GridStatistic::idw;
  throw UsageError("--stat must be max, mean, min or idw, not '" + name + "'");
}

PointGridder::PointGridder(const GridLattice& lattice, GridStatistic stat, double idw_radius, double idw_power)
    : g_(lattice), stat_(stat), inv_res_(1.0 / lattice.res), radius_(idw_radius), power_(idw_power) {
  if (!(idw_radius > 0) || !(idw_power > 0)) throw Error("IDW needs a positive radius and power");
  const std::size_t n = static_cast<std::size_t>(g_.width) * static_cast<std::size_t>(g_.height);
  // max and min start at the identity of their operation, so adding needs no test for "empty".
  const float start = stat == GridStatistic::max   ? -std::numeric_limits<float>::infinity()
                      : stat == GridStatistic::min ? std::numeric_limits<float>::infinity()
                                                   : 0.0f;
  if (stat == GridStatistic::max || stat == GridStatistic::min) value_.assign(n, start);
  if (stat == GridStatistic::idw) weight_.assign(n, 0.0);
  if (stat == GridStatistic::mean) count_.assign(n, 0);
  if (stat == GridStatistic::mean || stat == GridStatistic::idw) sum_.assign(n, 0.0);
}

void PointGridder::add_idw(double fc, double fr, float z) {
  // Cell centres sit at half-integer positions; visit those within the radius.
  const int c0 = std::max(0, static_cast<int>(std::ceil(fc - 0.5 - radius_)));
  const int c1 = std::min(g_.width - 1, static_cast<int>(std::floor(fc - 0.5 + radius_)));
  const int r0 = std::max(0, static_cast<int>(std::ceil(fr - 0.5 - radius_)));
  const int r1 = std::min(g_.height - 1, static_cast<int>(std::floor(fr - 0.5 + radius_)));
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      const double dc = fc - (c + 0.5), dr = fr - (r + 0.5);
      const double d2 = dc * dc + dr * dr;
      if (d2 > radius_ * radius_) continue;
      const double d = std::max(std::sqrt(d2), 1e-3);
      const double w = power_ == 2.0 ? 1.0 / (d * d) : std::pow(d, -power_);
      const std::size_t k =
          static_cast<std::size_t>(r) * static_cast<std::size_t>(g_.width) + static_cast<std::size_t>(c);
      weight_[k] += w;
      sum_[k] += w * z;
    }
  }
}

Grid<float> PointGridder::finish(std::int64_t* cells_with_returns) const {
  Grid<float> out(g_.width, g_.height, std::numeric_limits<float>::quiet_NaN());
  std::int64_t filled = 0;
  for (std::size_t k = 0; k < out.size(); ++k) {
    float v = std::numeric_limits<float>::quiet_NaN();
    switch (stat_) {
      case GridStatistic::max:
      case GridStatistic::min:
        if (std::isfinite(value_[k])) v = value_[k];
        break;
      case GridStatistic::mean:
        if (count_[k] > 0) v = static_cast<float>(sum_[k] / count_[k]);
        break;
      case GridStatistic::idw:
        if (weight_[k] > 0) v = static_cast<float>(sum_[k] / weight_[k]);
        break;
    }
    if (!std::isnan(v)) ++filled;
    out.values()[k] = v;
  }
  if (cells_with_returns) *cells_with_returns = filled;
  return out;
}

}  // namespace skyview
