// Dynamic scenes (the paper's Figure 12 idea): the zenith map made again only inside an added
// object's footprint (ZenithDepthMap::update_region) against a full build of the changed scene,
// at 1 m, for the synthetic city (meshed from its DSM) and Berlin's LoD2 CityGML sample
// (../shared/sample_data/city3d; skipped where absent). The added object is a 20 x 20 m block at
// the scene's centre, lower than its tallest roof. Embree's rebuild of the changed scene, which
// both ways need, is timed apart. Run: build/bench_zenith_update --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>

#include "skyview/raster/band_writer.h"
#include "skyview/render/zenith_depth_map.h"
#include "skyview/synthetic/synthetic.h"

#include "render_bench_scenes.h"

namespace {

using namespace skyview;

struct Change {
  Scene after;
  std::unique_ptr<RayScene> rays;
  ZenithDepthMap map;  // made from the scene before the change, then updated
  std::array<double, 2> lo{}, hi{};
};

ZenithOptions options() {
  ZenithOptions o;
  o.resolution = 1.0;
  return o;
}

SceneMesh block(const std::string& name, Vec3f lo, Vec3f hi) {
  SceneMesh m;
  m.name = name;
  for (int k = 0; k < 8; ++k)
    m.vertices.push_back({k & 1 ? hi[0] : lo[0], k & 2 ? hi[1] : lo[1], k & 4 ? hi[2] : lo[2]});
  const std::uint32_t q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : q) {
    m.triangles.push_back({f[0], f[1], f[2]});
    m.triangles.push_back({f[0], f[2], f[3]});
  }
  return m;
}

Change* change(int which) {
  static std::map<int, std::unique_ptr<Change>> made;
  if (auto it = made.find(which); it != made.end()) return it->second.get();
  const std::string path = render_bench_scene(which, "bench_zenith_update");
  if (path.empty()) return nullptr;
  auto c = std::make_unique<Change>();
  const Scene before = load_scene({path});
  c->map = ZenithDepthMap::build(before, RayScene(before), options());
  const auto b = before.bounds();
  const float cx = (b[0][0] + b[1][0]) / 2, cy = (b[0][1] + b[1][1]) / 2;
  c->after = before;
  c->after.meshes.push_back(block("added", {cx - 10, cy - 10, b[0][2]}, {cx + 10, cy + 10, (b[0][2] + b[1][2]) / 2}));
  c->rays = std::make_unique<RayScene>(c->after);
  c->lo = {cx - 10.0, cy - 10.0};
  c->hi = {cx + 10.0, cy + 10.0};
  if (c->map.update_region(c->after, *c->rays, options(), c->lo, c->hi) < 0) std::abort();
  if (!c->map.same_as(ZenithDepthMap::build(c->after, *c->rays, options()))) std::abort();
  return made.emplace(which, std::move(c)).first->second.get();
}

void BM_ZenithFullBuild(benchmark::State& state) {
  Change* c = change(int(state.range(0)));
  if (!c) return state.SkipWithError("sample data absent");
  for (auto _ : state) benchmark::DoNotOptimize(ZenithDepthMap::build(c->after, *c->rays, options()));
  state.counters["texels"] = double(c->map.width()) * c->map.height();
}

void BM_ZenithUpdate(benchmark::State& state) {
  Change* c = change(int(state.range(0)));
  if (!c) return state.SkipWithError("sample data absent");
  std::int64_t made = 0;
  for (auto _ : state) made = c->map.update_region(c->after, *c->rays, options(), c->lo, c->hi);
  state.counters["texels"] = double(made);
}

// Embree's BVH of the changed scene: needed by both ways.
void BM_RaySceneRebuild(benchmark::State& state) {
  Change* c = change(int(state.range(0)));
  if (!c) return state.SkipWithError("sample data absent");
  for (auto _ : state) benchmark::DoNotOptimize(RayScene(c->after));
}

BENCHMARK(BM_ZenithFullBuild)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ZenithUpdate)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RaySceneRebuild)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
