// Throughput of every horizon method in cell-directions per second on a synthetic city DSM.
// Run: ./build/bench_horizon [--benchmark_filter=...]; sizes via SKYVIEW_BENCH_SIZE (default 2000), or
// any raster via SKYVIEW_BENCH_DSM.
#include <benchmark/benchmark.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "skyview/horizon/horizon_engine.h"
#include "skyview/raster/raster_io.h"
#include "skyview/sky_view/sky_view.h"
#include "skyview/synthetic/synthetic.h"

namespace {

const skyview::Terrain& city(int size) {
  // SKYVIEW_BENCH_DSM names a raster to run on instead (a real city; SKYVIEW_BENCH_SIZE is then unused).
  if (const char* path = std::getenv("SKYVIEW_BENCH_DSM"); path && *path) {
    static const skyview::Terrain dsm = skyview::read_terrain(path, skyview::ReadOptions{});
    return dsm;
  }
  static std::map<int, skyview::Terrain> cache;
  auto it = cache.find(size);
  if (it == cache.end()) {
    it = cache
             .emplace(size,
                      skyview::rasterize(skyview::synthetic_city(1), size, size, skyview::local_grid(size, size, 1.0)))
             .first;
  }
  return it->second;
}

// Parameters as the command line starts them: sectors from grid north (the library's default is
// true north, which on a raster with grid convergence puts the sweep's axis directions just off the
// grid, onto its oblique path).
skyview::HorizonParams as_skyview_runs() {
  skyview::HorizonParams p;
  p.azimuth_origin = skyview::AzimuthOrigin::grid;
  return p;
}

int bench_size() {
  const char* s = std::getenv("SKYVIEW_BENCH_SIZE");
  return s ? std::atoi(s) : 2000;
}

void run(benchmark::State& state, const std::string& method, skyview::HorizonParams p) {
  const skyview::Terrain& t = city(bench_size());
  auto engine = skyview::make_horizon_engine(method, p);
  skyview::HorizonField field;
  for (auto _ : state) {
    skyview::ProgressCounter progress;
    engine->compute(t, skyview::Window::whole(t), field, progress);
    benchmark::DoNotOptimize(field.upper.data());
  }
  const double cell_directions = static_cast<double>(t.width()) * t.height() * p.directions;
  state.counters["cell_dirs_per_s"] =
      benchmark::Counter(cell_directions, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["cells"] = static_cast<double>(t.width()) * t.height();
}

void BM_Sampled16x16(benchmark::State& s) {
  skyview::HorizonParams p = as_skyview_runs();
  run(s, "sampled", p);
}
void BM_Sampled16x16NoEarlyExit(benchmark::State& s) {
  skyview::HorizonParams p = as_skyview_runs();
  p.early_exit = false;
  run(s, "sampled", p);
}
void BM_March16R100(benchmark::State& s) {
  skyview::HorizonParams p = as_skyview_runs();
  p.radius = 100;
  run(s, "march", p);
}
void BM_March16R100NoEarlyExit(benchmark::State& s) {
  skyview::HorizonParams p = as_skyview_runs();
  p.radius = 100;
  p.early_exit = false;
  run(s, "march", p);
}

// The arguments are the number of exact near steps (--samples; 64 is the default) and of far lines
// (--far-lines; 1 is the default). Of sixteen directions on this local grid, eight run along its
// axes and diagonals, where the sweep pushes each cell onto its own line (no near field, no query).
void BM_Sweep16(benchmark::State& s) {
  skyview::HorizonParams p = as_skyview_runs();
  p.samples = static_cast<int>(s.range(0));
  p.far_lines = static_cast<int>(s.range(1));
  run(s, "sweep", p);
}
// Fifteen directions: only north runs along the grid, so nearly every direction takes the general
// path (near field and hull queries) that sixteen share with the axes' and diagonals' exact push.
void BM_Sweep15(benchmark::State& s) {
  skyview::HorizonParams p = as_skyview_runs();
  p.directions = 15;
  p.samples = static_cast<int>(s.range(0));
  p.far_lines = static_cast<int>(s.range(1));
  run(s, "sweep", p);
}
// BM_Sweep16 as `skyview svf` runs the sweep: directions handed over one at a time into a few
// planes that the run reuses (each iteration faults in about two per worker, 64 MB each at
// 4000^2, and the workers' hull arenas), where BM_Sweep16 faults in and fills a whole 1 GB field.
// The sink only touches each plane; the products are BM_SvfStreamed16's.
void run_streamed(benchmark::State& state, const skyview::HorizonParams& p) {
  const skyview::Terrain& t = city(bench_size());
  auto engine = skyview::make_horizon_engine("sweep", p);
  skyview::HorizonField field;
  for (auto _ : state) {
    skyview::ProgressCounter progress;
    float touched = 0;
    engine->compute_directions(t, skyview::Window::whole(t), field, progress,
                               [&](int, int, const float* upper, const float*) { touched += upper[0]; });
    benchmark::DoNotOptimize(touched);
  }
  state.counters["cell_dirs_per_s"] = benchmark::Counter(static_cast<double>(t.width()) * t.height() * p.directions,
                                                         benchmark::Counter::kIsIterationInvariantRate);
}
// Near steps and far lines from the benchmark's arguments.
void run_streamed(benchmark::State& state, int directions) {
  skyview::HorizonParams p = as_skyview_runs();
  p.directions = directions;
  p.samples = static_cast<int>(state.range(0));
  p.far_lines = static_cast<int>(state.range(1));
  run_streamed(state, p);
}
void BM_Sweep16Streamed(benchmark::State& state) { run_streamed(state, 16); }
// Directions along the grid's lines (--azimuths grid-lines): every one exact, none with a near
// field or a far-field search. 4 (the axes) and 8 (and diagonals) price the slope-1/2 lines that
// 16 adds.
void BM_SweepGridLinesStreamed(benchmark::State& state) {
  skyview::HorizonParams p = as_skyview_runs();
  p.spacing = skyview::AzimuthSpacing::grid_lines;
  p.directions = static_cast<int>(state.range(0));
  run_streamed(state, p);
}
// The oblique cost as `skyview svf` pays it where few sectors run along the grid: with
// `--azimuth-origin north` on a projected raster, or a number of directions not a multiple of 8
// (of 15, only the first runs along the grid).
void BM_Sweep15Streamed(benchmark::State& state) { run_streamed(state, 15); }
void BM_Sweep16WithLower(benchmark::State& s) {
  skyview::HorizonParams p = as_skyview_runs();
  p.lower = true;
  run(s, "sweep", p);
}

// Horizons and lowest angles by the sweep, then the five products, computed by
// `products(terrain, whole window, engine)`. The counter is still cell-directions.
template <class Products>
void run_svf(benchmark::State& state, Products&& products) {
  const skyview::Terrain& t = city(bench_size());
  skyview::HorizonParams p = as_skyview_runs();
  p.lower = true;
  const auto engine = skyview::make_horizon_engine("sweep", p);
  for (auto _ : state) {
    const skyview::SkyViewProducts result = products(t, skyview::Window::whole(t), *engine);
    benchmark::DoNotOptimize(result.svf.data());
  }
  state.counters["cell_dirs_per_s"] = benchmark::Counter(static_cast<double>(t.width()) * t.height() * p.directions,
                                                         benchmark::Counter::kIsIterationInvariantRate);
}

// Every direction held, products summed at the end.
void BM_SvfWhole16(benchmark::State& state) {
  run_svf(state, [](const skyview::Terrain& t, const skyview::Window& w, const skyview::HorizonEngine& engine) {
    skyview::HorizonField field;
    skyview::ProgressCounter progress;
    engine.compute(t, w, field, progress);
    return skyview::sky_view_products(t, w, field, engine.radius(), skyview::EdgeMode::open);
  });
}

// What `skyview svf` runs (compute_sky_view): from 16 directions on, the products summed as the
// sweep hands the directions over.
void BM_SvfStreamed16(benchmark::State& state) {
  run_svf(state, [](const skyview::Terrain& t, const skyview::Window& w, const skyview::HorizonEngine& engine) {
    skyview::ProgressCounter progress;
    return skyview::compute_sky_view(engine, t, w, skyview::EdgeMode::open, progress);
  });
}

// The cost floor of the hull sweep's design, for judging any redesign against the 100 M
// cell-directions/s target: lines one cell apart (drift 0.3 cell per row, bands of 256 lines
// over both cores), one sample per line and row read linearly between cell centres, each pushed
// onto its line's upper hull (Andrew's monotone chain, float). No minor crossings, no exact near
// field, no angles written: what the sweep does is a superset of one of these.
// - PushTangent: the design. A sample's horizon is its tangent to the hull, which is its
//   neighbour once pushed: free.
// - DelayedQueries: what exactness along each cell's own ray needs. Samples join their hull 64 rows
//   late (the exact near field covers those), so a cell's tangent is a query: it asks the two
//   lines beside it, the nearest hull point first, else a bisection.
struct HullPoint {
  float t, z;
};
bool rises(const HullPoint& a, const HullPoint& b, const HullPoint& p) {
  return (a.z - p.z) * (b.t - p.t) < (b.z - p.z) * (a.t - p.t);
}
void push(HullPoint* h, int& n, const HullPoint& p) {
  while (n >= 2 && !rises(h[n - 2], h[n - 1], p)) --n;
  h[n++] = p;
}
float tangent_slope(const HullPoint* h, int n, const HullPoint& p) {
  int lo = n - 1;
  if (n > 1 && !rises(h[n - 2], h[n - 1], p)) {
    int hi = n - 1;  // rises into lo (or lo is the farthest point), not into hi
    lo = 0;
    while (hi - lo > 1) {
      const int mid = (lo + hi) / 2;
      (rises(h[mid - 1], h[mid], p) ? lo : hi) = mid;
    }
  }
  return (h[lo].z - p.z) / (h[lo].t - p.t);
}

// The floors' common frame: kFloorPasses passes over bands of `lines` hull lines each, the first
// band starting at minor index `first` and each next one kFloorBand on, on both cores. `walk(m0, arena, n)` runs
// one band from line m0 (arena: `lines` hulls of H + 1 points each; n: their sizes) and returns a
// sum that keeps its work from being optimised away.
constexpr int kFloorBand = 256, kFloorPasses = 16;
template <class Walk>
void run_floor(benchmark::State& state, const skyview::Terrain& t, int first, int lines, Walk&& walk) {
  const int W = t.width(), H = t.height(), bands = (W - first) / kFloorBand + 1;
  for (auto _ : state) {
    for (int pass = 0; pass < kFloorPasses; ++pass) {
      tbb::parallel_for(0, bands, [&](int band) {
        std::unique_ptr<HullPoint[]> arena(new HullPoint[static_cast<std::size_t>(lines) * (H + 1)]);
        std::vector<int> n(lines, 0);
        benchmark::DoNotOptimize(walk(first + band * kFloorBand, arena.get(), n));
      });
    }
  }
  state.counters["cell_dirs_per_s"] =
      benchmark::Counter(static_cast<double>(W) * H * kFloorPasses, benchmark::Counter::kIsIterationInvariantRate);
}

template <bool kDelayed>
void run_hull_floor(benchmark::State& state) {
  const skyview::Terrain& t = city(bench_size());
  const int W = t.width(), H = t.height();
  constexpr int kBand = kFloorBand, kLag = 64;
  constexpr double kDrift = 0.3;
  const float* z = t.heights.data();
  run_floor(state, t, -static_cast<int>(kDrift * H) - 1, kBand + 1, [&](int m0, HullPoint* arena, std::vector<int>& n) {
    float sink = 0;
    for (int row = 0; row < H; ++row) {
      const int sample_row = kDelayed ? row - kLag : row;
      if (sample_row >= 0) {
        const double shift = sample_row * kDrift, base = std::floor(shift);
        const float f = static_cast<float>(shift - base);
        const float* zr = z + static_cast<std::size_t>(sample_row) * W;
        for (int l = 0; l <= kBand; ++l) {
          const int c = m0 + static_cast<int>(base) + l;
          if (c < 0 || c + 1 >= W) continue;
          const HullPoint p{-static_cast<float>(sample_row), zr[c] + f * (zr[c + 1] - zr[c])};
          HullPoint* h = arena + static_cast<std::size_t>(l) * (H + 1);
          push(h, n[l], p);
          if (!kDelayed && n[l] > 1) sink += (h[n[l] - 2].z - p.z) / (h[n[l] - 2].t - p.t);
        }
      }
      if (kDelayed) {
        const int cell0 = m0 + static_cast<int>(std::floor(row * kDrift)) + 1;
        const float* zr = z + static_cast<std::size_t>(row) * W;
        for (int l = 0; l < kBand; ++l) {
          const int c = cell0 + l;
          if (c < 0 || c >= W) continue;
          const HullPoint p{-static_cast<float>(row), zr[c]};
          float best = -1e30f;
          for (int side = 0; side < 2; ++side) {
            if (n[l + side] > 0)
              best =
                  std::max(best, tangent_slope(arena + static_cast<std::size_t>(l + side) * (H + 1), n[l + side], p));
          }
          sink += best;
        }
      }
    }
    return sink;
  });
}
void BM_HullFloorPushTangent(benchmark::State& s) { run_hull_floor<false>(s); }
void BM_HullFloorDelayedQueries(benchmark::State& s) { run_hull_floor<true>(s); }

// A design the sweep does not have, for the oblique directions: a direction of slope 1/2 (26.57
// degrees from an axis, not 22.5) with lines half a cell apart. At every row each line sits on a
// cell centre or halfway between two (and crosses no column between rows), so every cell lies on a
// line: its exact horizon is its tangent once pushed, as PushTangent's, with no near field and no
// query, for twice the samples per cell. Same floor conditions as above.
void BM_HullFloorHalfSlopeLines(benchmark::State& state) {
  const skyview::Terrain& t = city(bench_size());
  const int W = t.width(), H = t.height(), lines = 2 * kFloorBand;
  const float* z = t.heights.data();
  run_floor(state, t, -(H / 2) - 1, lines, [&](int m0, HullPoint* arena, std::vector<int>& n) {
    float sink = 0;
    for (int row = 0; row < H; ++row) {
      const float* zr = z + static_cast<std::size_t>(row) * W;
      for (int l = 0; l < lines; ++l) {
        const int c = m0 + (l + row) / 2;  // line l sits at m0 + (l + row) / 2 cells
        const bool centre = (l + row) % 2 == 0;
        if (c < 0 || c + 1 >= W) continue;
        const HullPoint p{-static_cast<float>(row), centre ? zr[c] : 0.5f * (zr[c] + zr[c + 1])};
        HullPoint* h = arena + static_cast<std::size_t>(l) * (H + 1);
        push(h, n[l], p);
        if (centre && n[l] > 1) sink += (h[n[l] - 2].z - p.z) / (h[n[l] - 2].t - p.t);
      }
    }
    return sink;
  });
}

}  // namespace

BENCHMARK(BM_Sampled16x16)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_Sampled16x16NoEarlyExit)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_March16R100)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_March16R100NoEarlyExit)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_Sweep16)
    ->Args({64, 2})
    ->Args({16, 2})
    ->Args({8, 2})
    ->Args({1, 2})
    ->Args({64, 1})
    ->Args({32, 1})
    ->Args({16, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_Sweep15)
    ->Args({64, 2})
    ->Args({64, 1})
    ->Args({48, 1})
    ->Args({16, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_Sweep16Streamed)
    ->Args({64, 2})
    ->Args({64, 1})
    ->Args({56, 1})
    ->Args({48, 1})
    ->Args({40, 1})
    ->Args({32, 1})
    ->Args({16, 2})
    ->Args({16, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_SweepGridLinesStreamed)
    ->Arg(16)
    ->Arg(8)
    ->Arg(4)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);
BENCHMARK(BM_Sweep15Streamed)->Args({64, 1})->Args({16, 1})->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_Sweep16WithLower)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_SvfWhole16)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_SvfStreamed16)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_HullFloorPushTangent)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_HullFloorDelayedQueries)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_HullFloorHalfSlopeLines)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK_MAIN();
