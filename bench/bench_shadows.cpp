// Sun shadows on the points a camera sees, per method: time, and error against exact shadow rays
// (share of receivers whose sunlit state is wrong, at shadow edges and in interiors, leaks and
// acne; counters wrong, edge, interior, leak, acne in percent of receivers). Scenes: the synthetic
// city (a 401 m DSM, 1 m cells) seen from far and near, a synthetic footprint district, and the
// real LoD2 buildings of Berlin (../shared/sample_data/city3d, skipped where absent). Receivers are
// the first hits of a 400 x 300 pinhole camera's rays. Items are receivers.
// Run: build/bench_shadows --benchmark_min_time=0.5
#include <benchmark/benchmark.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <numbers>
#include <string>

#include "skyview/raster/band_writer.h"
#include "skyview/render/shadow_error.h"
#include "skyview/render/shadow_maps.h"
#include "skyview/scene/ray_scene.h"
#include "skyview/synthetic/synthetic.h"
#include "skyview/synthetic/synthetic_district.h"

namespace {

using skyview::ShadowMethod;
using skyview::Vec3f;

constexpr double kDeg = std::numbers::pi / 180.0;

struct View {
  std::unique_ptr<skyview::Scene> scene;
  std::unique_ptr<skyview::RayScene> rays;
  skyview::ShadowReceivers receivers;
  Vec3f eye;
  skyview::ShadowResult exact;
};

std::string temp_path(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "skyview_bench_shadows";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

std::unique_ptr<skyview::Scene> load(const std::string& name) {
  skyview::SceneLoadOptions o;
  if (name == "city") {
    const std::string path = temp_path("city.tif");
    const skyview::Terrain t =
        skyview::rasterize(skyview::synthetic_city(1), 401, 401, skyview::local_grid(401, 401, 1.0));
    skyview::WriteOptions w;
    w.overwrite = true;
    skyview::write_terrain(path, t, w);
    return std::make_unique<skyview::Scene>(skyview::load_scene({path}, o));
  }
  if (name == "district") {
    const std::string path = temp_path("district.gpkg");
    const skyview::SyntheticDistrict d = skyview::synthetic_district(500000, 6400000, 256);
    std::filesystem::remove(path);
    OGRSpatialReference utm;
    utm.importFromEPSG(32633);
    char* wkt = nullptr;
    utm.exportToWkt(&wkt);
    const std::string crs = wkt;
    CPLFree(wkt);
    skyview::write_district_footprints(path, d, crs, true);
    o.height_field = "height";
    o.base_field = "base";
    o.absolute_heights = false;
    return std::make_unique<skyview::Scene>(skyview::load_scene({path}, o));
  }
  // SKYVIEW_SHARED_DIR in the environment overrides the build's (a worktree's ../shared).
  const char* shared = std::getenv("SKYVIEW_SHARED_DIR");
  const std::string berlin =
      std::string(shared ? shared : SKYVIEW_SHARED_DIR) + "/sample_data/city3d/berlin_sample.citygml";
  if (!std::filesystem::exists(berlin)) return nullptr;
  return std::make_unique<skyview::Scene>(skyview::load_scene({berlin}, o));
}

// The first hits of a width x height pinhole camera at `eye` looking at `target` (vertical field
// of view `fov_deg`), with their normals turned towards the eye.
skyview::ShadowReceivers camera_hits(const skyview::RayScene& rays, Vec3f eye, Vec3f target, double fov_deg, int width,
                                     int height) {
  auto sub = [](Vec3f a, Vec3f b) { return Vec3f{a[0] - b[0], a[1] - b[1], a[2] - b[2]}; };
  auto norm = [](Vec3f a) {
    const float n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    return Vec3f{a[0] / n, a[1] / n, a[2] / n};
  };
  auto cross = [](Vec3f a, Vec3f b) {
    return Vec3f{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  };
  const Vec3f f = norm(sub(target, eye)), r = norm(cross(f, {0, 0, 1})), u = cross(r, f);
  const double h = std::tan(0.5 * fov_deg * kDeg), w = h * width / height;
  skyview::ShadowReceivers out;
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      const double a = ((i + 0.5) / width * 2 - 1) * w, b = (1 - (j + 0.5) / height * 2) * h;
      Vec3f d;
      for (int c = 0; c < 3; ++c) d[c] = static_cast<float>(f[c] + a * r[c] + b * u[c]);
      const auto hit = rays.intersect(eye, d);
      if (!hit) continue;
      Vec3f p;
      for (int c = 0; c < 3; ++c) p[c] = eye[c] + hit->t * d[c];
      out.points.push_back(p);
      out.normals.push_back(hit->normal);
    }
  }
  return out;
}

const Vec3f kSun = skyview::sun_direction_of(215 * kDeg, 30 * kDeg);

// Views by name: city_far, city_near, district, berlin.
View* view(const std::string& name) {
  static std::map<std::string, std::unique_ptr<View>> views;
  auto it = views.find(name);
  if (it != views.end()) return it->second.get();
  auto v = std::make_unique<View>();
  const std::string scene_name = name.rfind("city", 0) == 0 ? "city" : name;
  v->scene = load(scene_name);
  if (!v->scene) return views.emplace(name, nullptr).first->second.get();
  v->rays = std::make_unique<skyview::RayScene>(*v->scene);
  const auto b = v->scene->bounds();
  const Vec3f centre{0.5f * (b[0][0] + b[1][0]), 0.5f * (b[0][1] + b[1][1]), b[0][2]};
  const float size = std::max(b[1][0] - b[0][0], b[1][1] - b[0][1]);
  Vec3f target = centre;
  if (name == "city_near") {
    // Street level in the city's south-west quarter, looking north-east along the blocks.
    v->eye = {centre[0] - 0.2f * size, centre[1] - 0.2f * size, centre[2] + 12};
    target = {centre[0], centre[1], centre[2] + 5};
  } else {
    // The whole scene from above its south edge.
    v->eye = {centre[0], centre[1] - 0.9f * size, centre[2] + 0.6f * size};
  }
  v->receivers = camera_hits(*v->rays, v->eye, target, name == "city_near" ? 70 : 50, 400, 300);
  v->exact = skyview::sun_visibility(*v->rays, *v->scene, kSun, v->receivers, ShadowMethod::exact);
  return views.emplace(name, std::move(v)).first->second.get();
}

void run(benchmark::State& state, const std::string& name, ShadowMethod method) {
  View* v = view(name);
  if (!v) {
    state.SkipWithError("../shared/sample_data/city3d is absent");
    return;
  }
  skyview::ShadowOptions o;
  o.eye = v->eye;
  skyview::ShadowResult r;
  for (auto _ : state) {
    r = skyview::sun_visibility(*v->rays, *v->scene, kSun, v->receivers, method, o);
    benchmark::DoNotOptimize(r.visibility.data());
  }
  const skyview::ShadowError e = skyview::shadow_error(*v->rays, kSun, v->receivers, v->exact, r, o);
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
