// Sun shadows on the points a camera sees, per method: time, and error against exact shadow rays
// (share of receivers whose sunlit state is wrong, at shadow edges and in interiors, leaks and
// acne; counters wrong, edge, interior, leak, acne in percent of receivers). Scenes: the synthetic
// city (a 401 m DSM, 1 m cells) seen from far and near, a synthetic footprint district, and the
// real LoD2 buildings of Berlin (../shared/sample_data/city3d, skipped where absent). Receivers are
// the first hits of a 400 x 300 pinhole camera's rays. Items are receivers. The views are
// skyview/benchmark/shadow_benchmark.h's, which skyview bench --shadows runs too.
// Run: build/bench_shadows --benchmark_min_time=0.5
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "skyview/benchmark/shadow_benchmark.h"

namespace {

using skyview::ShadowMethod;

// Views by name (city_far, city_near, district, berlin), made once; null where the sample is absent.
const skyview::ShadowBenchView* view(const std::string& name) {
  static std::map<std::string, std::unique_ptr<skyview::ShadowBenchView>> views;
  static std::shared_ptr<const skyview::Scene> city;
  static std::shared_ptr<const skyview::RayScene> city_rays;
  auto it = views.find(name);
  if (it != views.end()) return it->second.get();
  const std::string work = (std::filesystem::temp_directory_path() / "skyview_bench_shadows").string();
  std::shared_ptr<const skyview::Scene> scene;
  std::shared_ptr<const skyview::RayScene> rays;
  if (name.rfind("city", 0) == 0) {
    if (!city) {
      city = skyview::load_shadow_bench_scene("city", work);
      city_rays = std::make_shared<const skyview::RayScene>(*city);
    }
    scene = city, rays = city_rays;
  } else if (name == "district") {
    scene = skyview::load_shadow_bench_scene("district", work);
  } else {
    // SKYVIEW_SHARED_DIR in the environment overrides the build's (a worktree's ../shared).
    const char* shared = std::getenv("SKYVIEW_SHARED_DIR");
    const std::string berlin =
        std::string(shared ? shared : SKYVIEW_SHARED_DIR) + "/sample_data/city3d/berlin_sample.citygml";
    if (!std::filesystem::exists(berlin)) return views.emplace(name, nullptr).first->second.get();
    scene = skyview::load_shadow_bench_scene(berlin, work);
  }
  auto v = std::make_unique<skyview::ShadowBenchView>(skyview::make_shadow_bench_view(name, scene, rays));
  return views.emplace(name, std::move(v)).first->second.get();
}

void run(benchmark::State& state, const std::string& name, ShadowMethod method) {
  const skyview::ShadowBenchView* v = view(name);
  if (!v) {
    state.SkipWithError("../shared/sample_data/city3d is absent");
    return;
  }
  skyview::ShadowOptions o;
  o.eye = v->eye;
  skyview::ShadowResult r;
  for (auto _ : state) {
    r = skyview::sun_visibility(*v->rays, *v->scene, skyview::shadow_bench_sun(), v->receivers, method, o);
    benchmark::DoNotOptimize(r.visibility.data());
  }
  const skyview::ShadowError e =
      skyview::shadow_error(*v->rays, skyview::shadow_bench_sun(), v->receivers, v->exact, r, o);
  state.counters["wrong%"] = 100 * e.wrong_share();
  state.counters["edge%"] = 100 * e.share(e.wrong_edge);
  state.counters["interior%"] = 100 * e.share(e.wrong_interior);
  state.counters["leak%"] = 100 * e.share(e.leaks);
  state.counters["acne%"] = 100 * e.share(e.acne);
  state.counters["map_ms"] = 1000 * r.map_seconds;
  state.counters["lookup_ms"] = 1000 * r.lookup_seconds;
  state.counters["MiB"] = static_cast<double>(r.map_bytes) / (1 << 20);
  state.counters["edges%"] = 100 * e.share(e.edge_receivers);
  state.counters["mean_abs"] = e.mean_abs;
  state.counters["receivers"] = static_cast<double>(v->receivers.points.size());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(v->receivers.points.size()));
}

void register_all() {
  for (const char* name : {"city_far", "city_near", "district", "berlin"}) {
    for (ShadowMethod m : {ShadowMethod::exact, ShadowMethod::pcf, ShadowMethod::vsm, ShadowMethod::lvsm,
                           ShadowMethod::csm, ShadowMethod::hsm}) {
      benchmark::RegisterBenchmark(("BM_Shadows/" + std::string(name) + "/" + skyview::shadow_method_name(m)).c_str(),
                                   [name = std::string(name), m](benchmark::State& s) { run(s, name, m); })
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
