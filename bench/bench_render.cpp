// Speed of skyview render's passes at 800x600 (the paper's Table 1): primary rays (Embree), then
// the large scale alone, large + fine, and large + fine + exposure, at 8x(8+8) and 16x(16+16), for
// a far and a near view of the synthetic city (meshed from its DSM, 1 m cells) and of Berlin's
// LoD2 CityGML sample (../shared/sample_data/city3d; skipped where absent). The zenith map is made
// once per scene, as the paper's. Run: build/bench_render --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>

#include "skyview/raster/band_writer.h"
#include "skyview/render/two_scale_visibility.h"
#include "skyview/sky/exposure_pyramid.h"
#include "skyview/sky/sky_models.h"
#include "skyview/synthetic/synthetic.h"

#include "render_bench_scenes.h"

namespace {

using namespace skyview;

struct Bench {
  Scene scene;
  std::unique_ptr<RayScene> rays;
  ZenithDepthMap zenith;
  Vec3d centre{};
  double reach = 0;  // half the scene's width
};

ExposureMap& sky_map() {
  static ExposureMap map = [] {
    // A year of an isotropic-free clear sky would take long here; a synthetic map with a sun band
    // and a bright sky costs the sampler the same.
    ExposureMap m(128, 128);
    for (int y = 0; y < 128; ++y) {
      for (int x = 0; x < 128; ++x) {
        m.band(ExposureBand::diffuse)[y * 128 + x] = 100.0f + y;
        m.band(ExposureBand::direct)[y * 128 + x] = (y > 40 && y < 70 && x > 30 && x < 100) ? 5000.0f : 0.0f;
      }
    }
    return m;
  }();
  return map;
}

Bench* bench(int which) {
  static std::map<int, std::unique_ptr<Bench>> made;
  auto it = made.find(which);
  if (it != made.end()) return it->second.get();
  auto b = std::make_unique<Bench>();
  const std::string path = render_bench_scene(which, "bench_render");
  if (path.empty()) return nullptr;
  b->scene = load_scene({path});
  b->rays = std::make_unique<RayScene>(b->scene);
  ZenithOptions zo;
  zo.resolution = 1.0;
  b->zenith = ZenithDepthMap::build(b->scene, *b->rays, zo);
  const auto bounds = b->scene.bounds();
  for (int k = 0; k < 3; ++k) b->centre[k] = (bounds[0][k] + bounds[1][k]) / 2 + b->scene.origin[k];
  b->centre[2] = bounds[0][2] + b->scene.origin[2] + 2;
  b->reach = (bounds[1][0] - bounds[0][0]) / 2;
  return made.emplace(which, std::move(b)).first->second.get();
}

// range(0): scene (0 synthetic city, 1 Berlin); (1): N = S; (2): 0 far, 1 near; (3): 0 large,
// 1 large + fine, 2 + exposure.
void BM_Render(benchmark::State& state) {
  Bench* b = bench(static_cast<int>(state.range(0)));
  if (!b) {
    state.SkipWithError("../shared/sample_data/city3d is absent");
    return;
  }
  const int n = static_cast<int>(state.range(1));
  const bool near = state.range(2) == 1;
  const int mode = static_cast<int>(state.range(3));
  CameraSpec spec;
  const double d = near ? 0.25 * b->reach : 1.2 * b->reach;
  spec.position = {b->centre[0] - d, b->centre[1] - d, b->centre[2] + (near ? 8 : 0.8 * b->reach)};
  spec.look_at = b->centre;
  spec.width = 800;
  spec.height = 600;
  const Camera camera(spec, b->scene.origin);
  TwoScaleOptions o;
  o.directions = o.samples = n;
  o.fine_scale = mode >= 1;
  std::optional<ExposurePyramid> pyramid;
  std::optional<ExposureSampler> sampler;
  if (mode == 2) {
    pyramid.emplace(sky_map());
    SamplerOptions so;
    so.max_sample_rows = std::max(1, sky_map().height() / n);  // n_s at most N: the paper's square map
    sampler.emplace(*pyramid, n, 0.0, so);
  }
  std::size_t hits = 0;
  for (auto _ : state) {
    const ViewBuffers view = render_view_buffers(*b->rays, camera);
    hits = view.hits();
    benchmark::DoNotOptimize(two_scale_visibility(view, camera, b->zenith, o, sampler ? &*sampler : nullptr));
  }
  state.counters["pixels_on_scene"] = static_cast<double>(hits);
}

void BM_PrimaryRays(benchmark::State& state) {
  Bench* b = bench(static_cast<int>(state.range(0)));
  if (!b) {
    state.SkipWithError("../shared/sample_data/city3d is absent");
    return;
  }
  CameraSpec spec;
  const double d = 1.2 * b->reach;
  spec.position = {b->centre[0] - d, b->centre[1] - d, b->centre[2] + 0.8 * b->reach};
  spec.look_at = b->centre;
  const Camera camera(spec, b->scene.origin);
  for (auto _ : state) benchmark::DoNotOptimize(render_view_buffers(*b->rays, camera));
}

BENCHMARK(BM_PrimaryRays)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Render)
    ->ArgsProduct({{0, 1}, {8, 16}, {0, 1}, {0, 1, 2}})
    ->ArgNames({"scene", "N", "near", "mode"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
