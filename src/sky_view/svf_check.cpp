#include "skyview/sky_view/svf_check.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "horizon/methods.h"
#include "horizon/ray_scan.h"
#include "skyview/core/error.h"
#include "skyview/sky_view/sky_view.h"

namespace skyview {
namespace {

// Reservoir sampling (Algorithm R) over the valid cells in one pass, with a hash of the cell's
// rank among them for its random number: the sample depends only on the raster and the seed.
std::vector<CellIndex> sample_valid_cells(const Terrain& terrain, int wanted, std::uint64_t seed, bool& exhaustive) {
  std::vector<CellIndex> chosen;
  chosen.reserve(static_cast<std::size_t>(wanted));
  std::uint64_t seen = 0;
  const std::uint64_t key = detail::splitmix64(seed);
  for (int row = 0; row < terrain.height(); ++row) {
    for (int col = 0; col < terrain.width(); ++col) {
      if (!terrain.valid(col, row)) continue;
      if (seen < static_cast<std::uint64_t>(wanted)) {
        chosen.push_back({col, row});
      } else {
        const std::uint64_t j = detail::splitmix64(seen ^ key) % (seen + 1);
        if (j < static_cast<std::uint64_t>(wanted)) chosen[j] = {col, row};
      }
      ++seen;
    }
  }
  exhaustive = seen <= static_cast<std::uint64_t>(wanted);
  // In raster order, so that neighbouring rays read neighbouring memory.
  std::sort(chosen.begin(), chosen.end(),
            [](const CellIndex& a, const CellIndex& b) { return a.row != b.row ? a.row < b.row : a.col < b.col; });
  return chosen;
}

double percentile99(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(std::ceil(0.99 * v.size())) - 1);
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

// The one-sided 95% confidence bound of the population's p99 of |value - reference| from the
// sampled cells' values (NaN where the run left a cell nodata; no bound under 300 cells), or
// their own p99 where they are every valid cell.
double p99_bound(const std::vector<float>& values, const std::vector<double>& reference, const ErrorStats& stats,
                 bool exhaustive) {
  if (exhaustive) return stats.p99;
  std::vector<double> abs_err;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isnan(values[i])) abs_err.push_back(std::abs(values[i] - reference[i]));
  }
  const std::int64_t rank = quantile_upper_rank(static_cast<std::int64_t>(abs_err.size()), 0.99, 0.95);
  if (rank == 0) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(abs_err.begin(), abs_err.begin() + (rank - 1), abs_err.end());
  return abs_err[static_cast<std::size_t>(rank - 1)];
}

}  // namespace

std::int64_t quantile_upper_rank(std::int64_t n, double q, double confidence) {
  if (n <= 0 || !(q > 0.0 && q < 1.0) || !(confidence > 0.0 && confidence < 1.0)) return 0;
  // The r-th smallest sample lies at or above the q-quantile unless r or more samples fall below
  // it: P = P(Binomial(n, q) <= r - 1).
  const double lq = std::log(q), lp = std::log1p(-q), ln = std::lgamma(static_cast<double>(n) + 1.0);
  double cdf = 0.0;
  for (std::int64_t k = 0; k < n; ++k) {
    const double kk = static_cast<double>(k);
    cdf += std::exp(ln - std::lgamma(kk + 1.0) - std::lgamma(static_cast<double>(n) - kk + 1.0) + kk * lq +
                    (static_cast<double>(n) - kk) * lp);
    if (cdf >= confidence) return k + 1;
  }
  return 0;
}

SvfCheck::SvfCheck(const Terrain& terrain, const SvfCheckOptions& options)
    : directions_(options.directions), curvature_(options.curvature) {
  if (options.cells < 1) throw Error("the svf check needs at least one cell");
  if (options.directions < 1 || options.directions > kSvfCheckMaxDirections)
    throw Error("the svf check's directions must be 1 to " + std::to_string(kSvfCheckMaxDirections));
  const auto start = std::chrono::steady_clock::now();
  cells_ = sample_valid_cells(terrain, options.cells, options.seed, exhaustive_);
  Window inner;
  const Terrain extended = extend_at_raster_edges(terrain, Window::whole(terrain), inner);
  std::vector<CellIndex> in_buffer = cells_;
  for (CellIndex& c : in_buffer) {
    c.col += inner.col0;
    c.row += inner.row0;
  }
  // Four times the sectors: their every fourth centre is the reference's (sector_azimuth is exact
  // under that scaling), so one walk gives both.
  constexpr int kFiner = kFinerSectors;
  HorizonField field;
  detail::exact_horizons_at(extended, in_buffer, kFiner * directions_, options.curvature,
                            direction_set_rotation(options.azimuth_origin, extended), field);
  reference_.resize(cells_.size());
  fine_reference_.resize(cells_.size());
  std::vector<double> sector_error(cells_.size());
  std::vector<float> fine(static_cast<std::size_t>(kFiner) * directions_), coarse(directions_);
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    for (int k = 0; k < kFiner * directions_; ++k) fine[k] = field.upper_at(i, k);
    for (int k = 0; k < directions_; ++k) coarse[k] = fine[static_cast<std::size_t>(kFiner) * k];
    reference_[i] = svf_horizontal(coarse.data(), directions_);
    fine_reference_[i] = svf_horizontal(fine.data(), kFiner * directions_);
    sector_error[i] = std::abs(reference_[i] - fine_reference_[i]);
  }
  sector_p99_ = percentile99(std::move(sector_error));
  seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

SvfCheckResult SvfCheck::measure(const Grid<float>& svf) const {
  const int n = static_cast<int>(cells_.size());
  std::vector<float> value(cells_.size()), reference(cells_.size()), fine(cells_.size());
  for (int i = 0; i < n; ++i) {
    value[i] = svf(cells_[i].col, cells_[i].row);
    reference[i] = static_cast<float>(reference_[i]);
    fine[i] = static_cast<float>(fine_reference_[i]);
  }
  SvfCheckResult r;
  const Grid<float> values(n, 1, std::move(value));
  r.error = compare_to_reference(values, Grid<float>(n, 1, std::move(reference)));
  r.error_fine = compare_to_reference(values, Grid<float>(n, 1, std::move(fine)));
  r.exhaustive = exhaustive_;
  r.p99_upper95 = p99_bound(values.values(), reference_, r.error, exhaustive_);
  r.fine_p99_upper95 = p99_bound(values.values(), fine_reference_, r.error_fine, exhaustive_);
  return r;
}

}  // namespace skyview
