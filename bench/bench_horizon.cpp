// Throughput of every horizon method in cell-directions per second on a synthetic city DSM.
// Run: ./build/bench_horizon [--benchmark_filter=...]; sizes via SKYVIEW_BENCH_SIZE (default 2000).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <map>
#include <string>

#include "skyview/horizon_engine.h"
#include "skyview/sky_view.h"
#include "skyview/synthetic.h"

namespace {

const skyview::Terrain& city(int size) {
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
  skyview::HorizonParams p;
  run(s, "sampled", p);
}
void BM_Sampled16x16NoEarlyExit(benchmark::State& s) {
  skyview::HorizonParams p;
  p.early_exit = false;
  run(s, "sampled", p);
}
void BM_March16R100(benchmark::State& s) {
  skyview::HorizonParams p;
  p.radius = 100;
  run(s, "march", p);
}
void BM_March16R100NoEarlyExit(benchmark::State& s) {
  skyview::HorizonParams p;
  p.radius = 100;
  p.early_exit = false;
  run(s, "march", p);
}
// The argument is the number of exact near steps (--samples); 64 is the default.
void BM_Sweep16(benchmark::State& s) {
  skyview::HorizonParams p;
  p.samples = static_cast<int>(s.range(0));
  run(s, "sweep", p);
}
void BM_Sweep16WithLower(benchmark::State& s) {
  skyview::HorizonParams p;
  p.lower = true;
  run(s, "sweep", p);
}

// Horizons and lowest angles by the sweep, then the five products, computed by
// `products(terrain, whole window, engine)`. The counter is still cell-directions.
template <class Products>
void run_svf(benchmark::State& state, Products&& products) {
  const skyview::Terrain& t = city(bench_size());
  skyview::HorizonParams p;
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

}  // namespace

BENCHMARK(BM_Sampled16x16)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_Sampled16x16NoEarlyExit)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_March16R100)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_March16R100NoEarlyExit)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_Sweep16)->Arg(64)->Arg(8)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_Sweep16WithLower)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_SvfWhole16)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_SvfStreamed16)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK_MAIN();
