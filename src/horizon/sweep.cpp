// Horizons in linear time per direction at unlimited radius. For one azimuth, parallel lines one
// cell apart cover the raster (sampled at every grid-line crossing). Walking a line from its
// far end back towards the viewer keeps the upper convex hull of the profile already seen; the
// horizon of the current cell is its tangent to that hull, which is also its neighbour once it
// is pushed onto the hull (Andrew's monotone chain), so each cell costs amortised O(1) and the
// search radius is unlimited. The idea follows the hull-based horizon algorithms of Stewart
// (1998, "Fast horizon computation at all points of a terrain with visibility and shading
// applications") and its sweep variants.
//
// Earth curvature: the apparent height of point j seen from i is z_j - c (t_j - t_i)^2. With
// transformed heights z' = z - c t^2 the slope from i to j becomes the true slope minus 2 c t_i,
// the same shift for every j, so the hull of z' still picks the true horizon exactly.
//
// Surface model: the ray-cast reference's mesh over cell centres, read where it can peak (every
// row and column crossing), as the march reads it. Exact along each cell's own ray for its first
// near_steps steps (default 64); beyond, a cell's slope is the nearer line's tangent (far_lines 1,
// the default), or interpolates its two neighbouring lines' tangents (far_lines 2): two queries
// instead of one, about as accurate as one line with twice the near steps and about 1.3x slower at
// 4000 x 4000 (measured in docs/benchmarks.md). Along the grid's axes and
// diagonals the lines run through cell centres, a cell's own ray is its line, and the issue's
// design is exact as it stands: each cell is pushed onto its line's hull and its horizon is the
// tangent found there (no near field, no query; about 2.8x faster per direction at 4000 x 4000).
// Along half slopes (k = ±1/2, --azimuths grid-lines) lines half a cell apart do the same at
// twice the pushes (cells_on_lines).
// With a radius, no hulls: every crossing within it along each cell's own ray (a vectorised march).
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "horizon/earth_curvature.h"
#include "horizon/methods.h"
#include "horizon/sweep_direction.h"
#include "skyview/core/error.h"
#include "skyview/core/large_pages.h"
#include "skyview/core/number_text.h"

namespace skyview::detail {
namespace {

using sweep::BandScratches;
using sweep::sweep_direction;

class SweepEngine final : public HorizonEngine {
 public:
  explicit SweepEngine(const HorizonParams& p) : p_(p) {
    if (p_.samples == 0) p_.samples = 64;
    if (p_.samples < 1 || p_.samples > 4096)
      throw UsageError("--samples (exact near steps) must be 1 to 4096 for sweep");
    if (p_.radius < 0.0 || !std::isfinite(p_.radius))
      throw UsageError("--radius must be positive (or 0 for unlimited)");
    if (p_.far_lines != 1 && p_.far_lines != 2) throw UsageError("--far-lines must be 1 or 2 for sweep");
  }
  std::string_view name() const override { return "sweep"; }
  std::string_view citation() const override {
    return "upper convex hull sweep along digital lines (after Stewart 1998, IEEE TVCG 4(1)); unlimited radius, or "
           "every crossing within --radius";
  }
  std::map<std::string, std::string> describe() const override {
    return {{"METHOD", "sweep"},
            {"DIRECTIONS", std::to_string(p_.directions)},
            {"RADIUS_M", p_.radius > 0 ? number_text(p_.radius) : "unlimited"},
            {"NEAR_STEPS", p_.radius > 0     ? "all within the radius"
                           : on_grid_lines() ? "none (every direction on the grid's lines: exact)"
                                             : std::to_string(p_.samples)},
            {"FAR_LINES", p_.radius > 0     ? "none (no hulls within a radius)"
                          : on_grid_lines() ? "none (every direction on the grid's lines: exact)"
                                            : std::to_string(p_.far_lines)}};
  }
  bool on_grid_lines() const { return p_.spacing == AzimuthSpacing::grid_lines; }
  double curvature_coefficient(const Terrain& terrain) const override {
    const double reach = p_.radius > 0 ? p_.radius : ground_diagonal(terrain);  // unlimited: the whole raster
    return detail::curvature_coefficient(p_, reach, terrain.frame.earth_radius());
  }
  double radius() const override { return p_.radius > 0 ? p_.radius : std::numeric_limits<double>::infinity(); }
  const HorizonParams& params() const override { return p_; }
  // Direction k's share of progress over `cells`: the shares add up to all of them.
  std::uint64_t direction_share(std::uint64_t cells, int k) const {
    const std::uint64_t n = static_cast<std::uint64_t>(p_.directions);
    return cells * (k + 1) / n - cells * k / n;
  }
  void compute_window(const Terrain& terrain, const Window& window, HorizonField& out,
                      ProgressCounter& progress) const override {
    out.resize(window.cols, window.rows, p_.directions, p_.lower);
    const Inputs in = inputs(terrain, out);
    BandScratches scratches;
    tbb::parallel_for(0, p_.directions, [&](int k) {
      progress.stop_if_cancelled();
      sweep(terrain, in, window, k, scratches, out.upper_plane(k), p_.lower ? out.lower_plane(k) : nullptr);
      progress.advance(direction_share(window.cells(), k));
    });
  }

  // Workers take directions in order; whichever finishes the next direction to hand over hands it
  // and any finished after it to `take`, one at a time (planes finished early wait). So only the
  // directions in progress, and those waiting for an earlier one, are held: a few planes, not all.
  // A slow `take` (compressing a GeoTIFF band) must not let the other workers race ahead: a worker
  // starts direction k only once k is within `ahead` of the next to hand over. The worker holding
  // that next direction never waits, so it always arrives; `take` runs isolated, so that a worker
  // inside it cannot pick up a new direction (which might wait for the very direction it hands).
  bool streams_directions() const override { return true; }
  void compute_window_directions(const Terrain& terrain, const Window& window, HorizonField& out,
                                 ProgressCounter& progress, const DirectionBatchSink& take) const override {
    out.resize(0, 0, p_.directions, false);
    out.cols = window.cols, out.rows = window.rows;
    const Inputs in = inputs(terrain, out);
    const std::size_t cells = window.cells();
    struct Planes {
      LargeBuffer<float> upper, lower;
    };
    std::mutex mutex;
    std::map<int, Planes> finished;
    std::vector<Planes> spare;
    int next = 0;  // the next direction to hand over
    std::condition_variable handed;
    const int ahead = 2 * tbb::this_task_arena::max_concurrency();
    bool handing = false;
    std::atomic<int> started{0};
    BandScratches scratches;
    tbb::parallel_for(0, p_.directions, [&](int) {
      // Before a direction is taken: every direction taken is finished and handed over, so no
      // worker waits for one that a cancelled worker left.
      progress.stop_if_cancelled();
      const int k = started++;
      Planes planes;
      {
        std::unique_lock<std::mutex> lock(mutex);
        handed.wait(lock, [&] { return k < next + ahead; });
        if (!spare.empty()) planes = std::move(spare.back()), spare.pop_back();
      }
      if (!planes.upper) {
        planes.upper = allocate_large<float>(cells);
        if (p_.lower) planes.lower = allocate_large<float>(cells);
      }
      sweep(terrain, in, window, k, scratches, planes.upper.get(), planes.lower.get());
      progress.advance(direction_share(cells, k));
      std::unique_lock<std::mutex> lock(mutex);
      finished.emplace(k, std::move(planes));
      if (handing) return;  // the worker handing over will find it
      handing = true;
      while (!finished.empty() && finished.begin()->first == next) {
        Planes ready = std::move(finished.begin()->second);
        finished.erase(finished.begin());
        lock.unlock();
        tbb::this_task_arena::isolate([&] { take(next, 1, ready.upper.get(), ready.lower.get()); });
        lock.lock();
        spare.push_back(std::move(ready));
        ++next;
        handed.notify_all();
      }
      handing = false;
    });
  }

 private:
  // What every direction reads: the curvature coefficient and the heights transposed, so that lines
  // advancing by columns read contiguous memory too.
  struct Inputs {
    double c;
    std::vector<double> azimuth;  // of each direction (HorizonField::set_azimuth)
    LargeBuffer<float> transposed;
  };
  Inputs inputs(const Terrain& terrain, const HorizonField& field) const {
    Inputs in;
    in.c = curvature_coefficient(terrain);
    for (int k = 0; k < p_.directions; ++k) in.azimuth.push_back(field.set_azimuth(k));
    const int W = terrain.width(), H = terrain.height();
    in.transposed = allocate_large<float>(static_cast<std::size_t>(W) * H);
    // In tiles, so that both the reads and the writes stay within cache lines already loaded; bands
    // of columns in parallel (each writes its own rows of the copy), which no direction can start
    // without (about 0.1 s of one core at 4000 x 4000).
    constexpr int kTile = 64;
    tbb::parallel_for(0, (W + kTile - 1) / kTile, [&](int tile) {
      const int c0 = tile * kTile;
      for (int r0 = 0; r0 < H; r0 += kTile) {
        for (int col = c0; col < std::min(W, c0 + kTile); ++col) {
          for (int r = r0; r < std::min(H, r0 + kTile); ++r)
            in.transposed[static_cast<std::size_t>(col) * H + r] = terrain.heights(col, r);
        }
      }
    });
    return in;
  }
  void sweep(const Terrain& terrain, const Inputs& in, const Window& window, int k, BandScratches& scratches,
             float* upper, float* lower) const {
    sweep_direction(terrain, in.transposed.get(), window, in.azimuth[static_cast<std::size_t>(k)], in.c, p_.samples,
                    p_.far_lines, p_.early_exit, radius(), scratches, upper, lower);
  }

  HorizonParams p_;
};

}  // namespace

std::unique_ptr<HorizonEngine> make_sweep_engine(const HorizonParams& params) {
  return std::make_unique<SweepEngine>(params);
}

}  // namespace skyview::detail
