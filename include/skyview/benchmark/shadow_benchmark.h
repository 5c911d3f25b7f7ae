#pragma once
// The shadow-map family against exact shadow rays on the views of docs/shadows.md's table: the
// synthetic city (a 401 m DSM of 1 m cells) from far above its south edge and from 12 m above a
// street, a synthetic footprint district, and any further scene (Berlin's LoD2 sample in the table)
// from far. Receivers are the first hits of a 400 x 300 pinhole camera's rays; the sun at azimuth
// 215°, elevation 30°. bench/bench_shadows.cpp (Google Benchmark) and `skyview bench --shadows`
// share these views and this error.
#include <nlohmann/json.hpp>

#include <memory>
#include <string>
#include <vector>

#include "skyview/render/shadow_error.h"
#include "skyview/render/shadow_maps.h"
#include "skyview/scene/ray_scene.h"
#include "skyview/scene/scene.h"

namespace skyview {

struct ShadowBenchView {
  std::string name;
  std::shared_ptr<const Scene> scene;
  std::shared_ptr<const RayScene> rays;
  ShadowReceivers receivers;
  Vec3f eye{0, 0, 0};
  ShadowResult exact;  // the reference on these receivers
};

// The sun of every view: azimuth 215°, elevation 30°.
Vec3f shadow_bench_sun();

// The synthetic city ("city") or district ("district"), written as files under `work_dir` and
// loaded as skyview scene loads them, or any scene input by its path.
std::shared_ptr<const Scene> load_shadow_bench_scene(const std::string& name_or_path, const std::string& work_dir);

// The view `name` of `scene`: "city_near" from street level in the scene's south-west quarter
// looking north-east (70° field of view), any other name from far above the south edge (50°).
// Traces the exact rays once.
ShadowBenchView make_shadow_bench_view(const std::string& name, std::shared_ptr<const Scene> scene,
                                       std::shared_ptr<const RayScene> rays = nullptr);

// The first hits of a width x height pinhole camera at `eye` looking at `target`, normals turned
// towards the eye.
ShadowReceivers camera_hits(const RayScene& rays, Vec3f eye, Vec3f target, double fov_deg, int width, int height);

struct ShadowBenchRow {
  std::string view;
  ShadowMethod method = ShadowMethod::exact;
  double seconds = 0;      // median of the runs
  double cpu_seconds = 0;  // the process's CPU time per run (user + system), for a loaded machine
  ShadowResult result;     // of the last run (map and lookup times, memory)
  ShadowError error;
};

// Runs `method` `repeat` times on the view with default options (the view's eye) and judges it.
ShadowBenchRow run_shadow_bench(const ShadowBenchView& view, ShadowMethod method, int repeat);

// The table of docs/shadows.md (view, method, ms, CPU ms, map ms, lookup ms, MiB, wrong %, at edges %,
// interior %, leak %, acne %, edge band %, mean abs, receivers) and the same as JSON.
std::string shadow_bench_markdown(const std::vector<ShadowBenchRow>& rows);
nlohmann::json shadow_bench_json(const std::vector<ShadowBenchRow>& rows);

}  // namespace skyview
