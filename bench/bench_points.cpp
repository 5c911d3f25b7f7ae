// Speed of point queries: observers 1.1 m above a synthetic city (1 m cells), horizons along their
// own rays by the march (the default) and by the Embree ray cast (the reference), 64 directions,
// to the raster's edge. Items are observers. Run: build/bench_points --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <map>
#include <random>
#include <vector>

#include "skyview/horizon/point_horizons.h"
#include "skyview/synthetic/synthetic.h"

namespace {

const skyview::Terrain& city(int size) {
  static std::map<int, skyview::Terrain> cities;
  auto it = cities.find(size);
  if (it == cities.end())
    it = cities
             .emplace(size,
                      skyview::rasterize(skyview::synthetic_city(1), size, size, skyview::local_grid(size, size, 1.0)))
             .first;
  return it->second;
}

std::vector<skyview::Observer> observers(int size, int n) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> pos(1.0, size - 2.0);
  std::vector<skyview::Observer> o;
  for (int i = 0; i < n; ++i) o.push_back({pos(rng), pos(rng), 1.1});
  return o;
}

void run(benchmark::State& state, const char* method) {
  const int size = static_cast<int>(state.range(0));
  const skyview::Terrain& t = city(size);
  const std::vector<skyview::Observer> obs = observers(size, 200);
  skyview::PointHorizonOptions o;
  o.params.directions = 64;
  o.params.curvature = "off";
  o.method = method;
  for (auto _ : state) benchmark::DoNotOptimize(skyview::point_horizons(t, obs, o));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(obs.size()));
}

void BM_PointsMarch(benchmark::State& state) { run(state, "march"); }
void BM_PointsRaycast(benchmark::State& state) { run(state, "raycast"); }
BENCHMARK(BM_PointsMarch)->Arg(401)->Arg(1001)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PointsRaycast)->Arg(401)->Arg(1001)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
