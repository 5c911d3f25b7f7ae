#pragma once
// Returns onto cells: the per-cell maximum, mean or minimum of the returns whose position falls
// in the cell, or an inverse-distance-weighted mean of the returns within a radius of its centre.
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "skyview/core/grid.h"

namespace skyview {

enum class GridStatistic { max, mean, min, idw };

// "max", "mean", "min" or "idw"; throws skyview::Error otherwise.
GridStatistic parse_grid_statistic(const std::string& name);

struct GridLattice {
  int width = 0, height = 0;
  double x0 = 0, y1 = 0, res = 1;  // top-left corner and square cell size, north up
};

class PointGridder {
 public:
  // IDW: weight 1/d^power for returns within `idw_radius` cells of a cell centre (d is clamped
  // at 1e-3 cell so a return on a centre dominates without dividing by zero).
  PointGridder(const GridLattice& lattice, GridStatistic stat, double idw_radius = 1.0, double idw_power = 2.0);

  void add(double x, double y, float z) {
    const double fc = (x - g_.x0) * inv_res_, fr = (g_.y1 - y) * inv_res_;
    if (stat_ == GridStatistic::idw) return add_idw(fc, fr, z);
    if (!(fc >= 0 && fr >= 0 && fc < g_.width && fr < g_.height)) return;
    const std::size_t k =
        static_cast<std::size_t>(fr) * static_cast<std::size_t>(g_.width) + static_cast<std::size_t>(fc);
    switch (stat_) {
      case GridStatistic::max:
        value_[k] = std::max(value_[k], z);
        break;
      case GridStatistic::min:
        value_[k] = std::min(value_[k], z);
        break;
      default:
        sum_[k] += z, ++count_[k];
        break;
    }
  }

  // The gridded heights (NaN where no return contributed) and the number of such cells.
  Grid<float> finish(std::int64_t* cells_with_returns = nullptr) const;

 private:
  void add_idw(double fc, double fr, float z);
  GridLattice g_;
  GridStatistic stat_;
  double inv_res_, radius_, power_;
  std::vector<float> value_;  // running max or min
  std::vector<std::uint32_t> count_;
  std::vector<double> weight_, sum_;  // sums of weights and of (weighted) heights
};

}  // namespace skyview
