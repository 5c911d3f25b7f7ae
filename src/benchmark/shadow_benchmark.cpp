// The views, runs and table of the shadow-map benchmark (bench/bench_shadows.cpp and skyview bench
// --shadows).
#include "skyview/benchmark/shadow_benchmark.h"

#include <ogr_spatialref.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "skyview/raster/band_writer.h"
#include "skyview/synthetic/synthetic.h"
#include "skyview/synthetic/synthetic_district.h"

namespace skyview {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

}  // namespace

Vec3f shadow_bench_sun() { return sun_direction_of(215 * kDeg, 30 * kDeg); }

std::shared_ptr<const Scene> load_shadow_bench_scene(const std::string& name, const std::string& work_dir) {
  SceneLoadOptions o;
  std::filesystem::create_directories(work_dir);
  if (name == "city") {
    const std::string path = (std::filesystem::path(work_dir) / "city.tif").string();
    const Terrain t = rasterize(synthetic_city(1), 401, 401, local_grid(401, 401, 1.0));
    WriteOptions w;
    w.overwrite = true;
    write_terrain(path, t, w);
    auto scene = std::make_shared<const Scene>(load_scene({path}, o));
    std::filesystem::remove(path);
    return scene;
  }
  if (name == "district") {
    const std::string path = (std::filesystem::path(work_dir) / "district.gpkg").string();
    const SyntheticDistrict d = synthetic_district(500000, 6400000, 256);
    std::filesystem::remove(path);
    OGRSpatialReference utm;
    utm.importFromEPSG(32633);
    char* wkt = nullptr;
    utm.exportToWkt(&wkt);
    const std::string crs = wkt;
    CPLFree(wkt);
    write_district_footprints(path, d, crs, true);
    o.height_field = "height";
    o.base_field = "base";
    o.absolute_heights = false;
    auto scene = std::make_shared<const Scene>(load_scene({path}, o));
    std::filesystem::remove(path);
    return scene;
  }
  return std::make_shared<const Scene>(load_scene({name}, o));
}

ShadowReceivers camera_hits(const RayScene& rays, Vec3f eye, Vec3f target, double fov_deg, int width, int height) {
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
  ShadowReceivers out;
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

ShadowBenchView make_shadow_bench_view(const std::string& name, std::shared_ptr<const Scene> scene,
                                       std::shared_ptr<const RayScene> rays) {
  ShadowBenchView v;
  v.name = name;
  v.scene = std::move(scene);
  v.rays = rays ? std::move(rays) : std::make_shared<const RayScene>(*v.scene);
  const auto b = v.scene->bounds();
  const Vec3f centre{0.5f * (b[0][0] + b[1][0]), 0.5f * (b[0][1] + b[1][1]), b[0][2]};
  const float size = std::max(b[1][0] - b[0][0], b[1][1] - b[0][1]);
  Vec3f target = centre;
  const bool near = name == "city_near";
  if (near) {
    // Street level in the city's south-west quarter, looking north-east along the blocks.
    v.eye = {centre[0] - 0.2f * size, centre[1] - 0.2f * size, centre[2] + 12};
    target = {centre[0], centre[1], centre[2] + 5};
  } else {
    // The whole scene from above its south edge.
    v.eye = {centre[0], centre[1] - 0.9f * size, centre[2] + 0.6f * size};
  }
  v.receivers = camera_hits(*v.rays, v.eye, target, near ? 70 : 50, 400, 300);
  v.exact = sun_visibility(*v.rays, *v.scene, shadow_bench_sun(), v.receivers, ShadowMethod::exact);
  return v;
}

ShadowBenchRow run_shadow_bench(const ShadowBenchView& v, ShadowMethod method, int repeat) {
  ShadowOptions o;
  o.eye = v.eye;
  ShadowBenchRow row;
  row.view = v.name;
  row.method = method;
  std::vector<double> times;
  const double cpu0 = cpu_seconds();
  for (int k = 0; k < std::max(1, repeat); ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    row.result = sun_visibility(*v.rays, *v.scene, shadow_bench_sun(), v.receivers, method, o);
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  row.cpu_seconds = (cpu_seconds() - cpu0) / times.size();
  std::sort(times.begin(), times.end());
  row.seconds = times[times.size() / 2];
  row.error = shadow_error(*v.rays, shadow_bench_sun(), v.receivers, v.exact, row.result, o);
  return row;
}

std::string shadow_bench_markdown(const std::vector<ShadowBenchRow>& rows) {
  std::string md =
      "| view | method | ms | CPU ms | map ms | lookup ms | MiB | wrong % | at edges % | interior % | leak % | acne % "
      "| "
      "edge band % | mean abs | receivers |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  char line[512];
  for (const ShadowBenchRow& r : rows) {
    const ShadowError& e = r.error;
    std::snprintf(line, sizeof line,
                  "| %s | %s | %.0f | %.0f | %.0f | %.0f | %.1f | %.3f | %.3f | %.3f | %.3f | %.3f | %.2f | %.4f | %zu "
                  "|\n",
                  r.view.c_str(), shadow_method_name(r.method).c_str(), 1000 * r.seconds, 1000 * r.cpu_seconds,
                  1000 * r.result.map_seconds, 1000 * r.result.lookup_seconds, r.result.map_bytes / 1048576.0,
                  100 * e.wrong_share(), 100 * e.share(e.wrong_edge), 100 * e.share(e.wrong_interior),
                  100 * e.share(e.leaks), 100 * e.share(e.acne), 100 * e.share(e.edge_receivers), e.mean_abs,
                  e.receivers);
    md += line;
  }
  return md;
}

nlohmann::json shadow_bench_json(const std::vector<ShadowBenchRow>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const ShadowBenchRow& r : rows) {
    const ShadowError& e = r.error;
    out.push_back({{"view", r.view},
                   {"method", shadow_method_name(r.method)},
                   {"seconds", r.seconds},
                   {"cpu_seconds", r.cpu_seconds},
                   {"map_seconds", r.result.map_seconds},
                   {"lookup_seconds", r.result.lookup_seconds},
                   {"map_bytes", r.result.map_bytes},
                   {"receivers", e.receivers},
                   {"wrong_share", e.wrong_share()},
                   {"wrong_edge_share", e.share(e.wrong_edge)},
                   {"wrong_interior_share", e.share(e.wrong_interior)},
                   {"leak_share", e.share(e.leaks)},
                   {"acne_share", e.share(e.acne)},
                   {"edge_receivers_share", e.share(e.edge_receivers)},
                   {"mean_abs", e.mean_abs}});
  }
  return out;
}

}  // namespace skyview
