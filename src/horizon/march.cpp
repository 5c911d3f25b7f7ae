// Marching along each direction through every row and column crossing up to the radius,
// interpolating between cell centres: the classic exhaustive horizon search (as in
// r.horizon, SAGA and RVT), slow but without sampling gaps.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "methods.h"
#include "ray_scan.h"
#include "skyview/core/number_text.h"

namespace skyview::detail {
namespace {

struct EveryCrossing {
  double radius;
  static constexpr bool kDenseSteps = true;
  // Row and column crossings in order of distance: the shared mesh is linear inside each
  // triangle with valley creases, so along a ray it peaks on grid lines, and only there. From a
  // cell centre the i-th column crossing is i steps away; from a point between centres (point
  // queries) it is i - phase steps away, phase being how far the point is past its last line.
  template <class Visit>
  void walk(double col, double row, double col_per_m, double row_per_m, double max_distance, double curvature,
            Visit&& visit) const {
    constexpr double kNever = std::numeric_limits<double>::infinity();
    const double step_c = col_per_m != 0.0 ? 1.0 / std::abs(col_per_m) : kNever;
    const double step_r = row_per_m != 0.0 ? 1.0 / std::abs(row_per_m) : kNever;
    const double phase_c = col_per_m > 0.0 ? col - std::floor(col) : std::ceil(col) - col;
    const double phase_r = row_per_m > 0.0 ? row - std::floor(row) : std::ceil(row) - row;
    const double limit = std::min(radius, max_distance);
    long long i = 1, j = 1;
    for (;;) {
      const double dc = (i - phase_c) * step_c, dr = (j - phase_r) * step_r;
      const double d = std::min(dc, dr);
      if (!(d <= limit)) return;
      // A diagonal step crosses both lines at once (within rounding): one visit.
      if (dc <= dr * (1.0 + 1e-12)) ++i;
      if (dr <= dc * (1.0 + 1e-12)) ++j;
      const double next = visit(d, 1.0 / d, curvature * d * d);
      if (next < 0.0) return;
      if (next > d) {  // skip to the first crossings beyond `next`
        i = std::max(i, static_cast<long long>(std::min(next / step_c + phase_c, 1e18)) + 1);
        j = std::max(j, static_cast<long long>(std::min(next / step_r + phase_r, 1e18)) + 1);
      }
    }
  }
};

class MarchEngine final : public HorizonEngine {
 public:
  explicit MarchEngine(const HorizonParams& p) : p_(p) {
    if (p_.radius == 0.0) p_.radius = 500.0;
  }
  std::string_view name() const override { return "march"; }
  std::string_view citation() const override {
    return "exhaustive line march over every cell crossing (cf. GRASS r.horizon, SAGA Sky View Factor)";
  }
  std::map<std::string, std::string> describe() const override {
    return {{"METHOD", "march"}, {"DIRECTIONS", std::to_string(p_.directions)}, {"RADIUS_M", number_text(p_.radius)}};
  }
  double radius() const override { return p_.radius; }
  const HorizonParams& params() const override { return p_; }
  void compute_window(const Terrain& terrain, const Window& window, HorizonField& out,
                      ProgressCounter& progress) const override {
    ScanSettings s = scan_settings(p_, terrain);
    scan_rays(terrain, window, out, progress, s, EveryCrossing{p_.radius});
  }

 private:
  HorizonParams p_;
};

}  // namespace

void exact_horizons_at(const Terrain& extended, const std::vector<CellIndex>& cells, int directions, double curvature,
                       double sector_rotation, HorizonField& out) {
  ScanSettings s;
  s.directions = directions;
  s.curvature = curvature;
  out.sector_rotation = sector_rotation;
  out.sectors = DirectionSet::uniform(directions);
  scan_cells(extended, cells, out, s, EveryCrossing{std::numeric_limits<double>::infinity()});
}

void march_point_horizons(const Terrain& extended, const std::vector<EyePoint>& eyes, int directions,
                          double sector_rotation, double radius, double curvature, bool early_exit,
                          std::vector<float>& out, std::vector<std::vector<std::vector<RisingStep>>>* rising,
                          ProgressCounter* progress) {
  ScanSettings s;
  s.directions = directions;
  s.curvature = curvature;
  s.early_exit = early_exit;
  s.max_distance = radius;
  HorizonField sectors;  // only its direction set: the scanner's azimuths
  sectors.sector_rotation = sector_rotation;
  sectors.sectors = DirectionSet::uniform(directions);
  const RayScanner<EveryCrossing> scanner(extended, s, EveryCrossing{radius}, sectors);
  const std::size_t n = eyes.size();
  out.assign(n * directions, std::numeric_limits<float>::quiet_NaN());
  if (rising) rising->assign(n, {});
  // Observers in Morton order of their cells, so that a thread's consecutive observers read nearby
  // heights: rays cross the buffer and each sample is otherwise a cache miss.
  std::vector<std::pair<std::uint64_t, std::size_t>> order(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t code = 0;
    if (!std::isnan(eyes[i].z)) {
      const auto cx = static_cast<std::uint32_t>(eyes[i].col), cy = static_cast<std::uint32_t>(eyes[i].row);
      for (int bit = 0; bit < 32; ++bit)
        code |= (std::uint64_t{(cx >> bit) & 1u} << (2 * bit)) | (std::uint64_t{(cy >> bit) & 1u} << (2 * bit + 1));
    }
    order[i] = {code, i};
  }
  std::sort(order.begin(), order.end());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t j = r.begin(); j != r.end(); ++j) {
      const std::size_t i = order[j].second;
      if (std::isnan(eyes[i].z)) continue;
      std::vector<std::vector<RisingStep>>* steps = nullptr;
      if (rising) {
        (*rising)[i].resize(directions);
        steps = &(*rising)[i];
      }
      scanner.scan_from(eyes[i].col, eyes[i].row, eyes[i].z, 0.0, out.data() + i * directions, nullptr, 1, steps);
      if (progress) progress->advance(1);
    }
  });
}

std::unique_ptr<HorizonEngine> make_march_engine(const HorizonParams& params) {
  return std::make_unique<MarchEngine>(params);
}

}  // namespace skyview::detail
