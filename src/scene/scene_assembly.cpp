#include "scene/scene_assembly.h"

#include <ogr_spatialref.h>

#include <cmath>
#include <limits>

namespace skyview {
namespace {

constexpr std::size_t kExamples = 3;  // names a warning line quotes

std::string tally_text(std::int64_t count, const std::string& what) {
  return std::to_string(count) + " " + what + (count == 1 ? "" : "s");
}

// Twice the area of the triangle, computed from the float corners the scene stores: a triangle
// that float rounding flattens is as degenerate as one given flat.
double doubled_area(const Vec3f& a, const Vec3f& b, const Vec3f& c) {
  const double u[3] = {double(b[0]) - a[0], double(b[1]) - a[1], double(b[2]) - a[2]};
  const double v[3] = {double(c[0]) - a[0], double(c[1]) - a[1], double(c[2]) - a[2]};
  const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  return std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

}  // namespace

void SceneAssembly::begin_input(const SceneInputReport& report, OGRCoordinateTransformation* to_scene) {
  scene_.report.inputs.push_back(report);
  to_scene_ = to_scene;
  skipped_.clear();
  dropped_.clear();
  surfaces_.clear();
}

void SceneAssembly::add(SourceMesh&& mesh, bool in_scene_crs) {
  SceneInputReport& input = scene_.report.inputs.back();
  std::vector<Vec3d>& v = mesh.vertices;
  // Into the scene's CRS: a point the transformation cannot take becomes NaN, and its triangles go.
  if (to_scene_ && !in_scene_crs && !v.empty()) {
    std::vector<double> x(v.size()), y(v.size()), z(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) x[i] = v[i][0], y[i] = v[i][1], z[i] = v[i][2];
    std::vector<int> ok(v.size(), 0);
    to_scene_->Transform(v.size(), x.data(), y.data(), z.data(), nullptr, ok.data());
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = ok[i] ? Vec3d{x[i], y[i], z[i]} : Vec3d{nan, nan, nan};
  }
  std::vector<Vec3f> local(v.size());
  std::vector<char> finite(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (int k = 0; k < 3; ++k) local[i][k] = static_cast<float>(v[i][k] - scene_.origin[k]);
    finite[i] = std::isfinite(local[i][0]) && std::isfinite(local[i][1]) && std::isfinite(local[i][2]);
  }
  SceneMesh out;
  out.name = std::move(mesh.name);
  out.source = input.path;
  std::vector<std::uint32_t> renumber(v.size(), std::numeric_limits<std::uint32_t>::max());
  std::int64_t bad_index = 0, non_finite = 0, degenerate = 0;
  for (const auto& t : mesh.triangles) {
    if (t[0] >= v.size() || t[1] >= v.size() || t[2] >= v.size()) {
      ++bad_index;
      continue;
    }
    if (!finite[t[0]] || !finite[t[1]] || !finite[t[2]]) {
      ++non_finite;
      continue;
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || !(doubled_area(local[t[0]], local[t[1]], local[t[2]]) > 0)) {
      ++degenerate;
      continue;
    }
    std::array<std::uint32_t, 3> kept;
    for (int k = 0; k < 3; ++k) {
      std::uint32_t& n = renumber[t[k]];
      if (n == std::numeric_limits<std::uint32_t>::max()) {
        n = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(local[t[k]]);
      }
      kept[k] = n;
    }
    out.triangles.push_back(kept);
  }
  if (out.triangles.empty()) {
    // Named by what left it empty: nothing given, only non-finite corners, only flat triangles.
    const std::string why = mesh.triangles.empty()                                ? "empty"
                            : non_finite >= degenerate && non_finite >= bad_index ? "only non-finite vertices"
                            : degenerate >= bad_index                             ? "only degenerate triangles"
                                                                                  : "only indices out of range";
    skip(out.name, why);
    return;
  }
  if (bad_index > 0) drop_triangles(bad_index, "indices out of range", out.name);
  if (non_finite > 0) drop_triangles(non_finite, "non-finite vertices", out.name);
  if (degenerate > 0) drop_triangles(degenerate, "degenerate", out.name);
  ++input.meshes;
  input.triangles += static_cast<std::int64_t>(out.triangles.size());
  ++scene_.report.meshes_loaded;
  scene_.meshes.push_back(std::move(out));
}

void SceneAssembly::tally(std::map<std::string, Tally>& tallies, std::int64_t count, const std::string& why,
                          const std::string& object) {
  Tally& t = tallies[why];
  t.count += count;
  if (object.empty() || (!t.examples.empty() && t.examples.back() == object)) return;
  ++t.objects;
  if (t.examples.size() < kExamples) t.examples.push_back(object);
}

void SceneAssembly::skip(const std::string& object, const std::string& why) {
  ++scene_.report.meshes_skipped;
  ++scene_.report.inputs.back().meshes_skipped;
  tally(skipped_, 1, why, object);
}

void SceneAssembly::drop_triangles(std::int64_t count, const std::string& why, const std::string& object) {
  scene_.report.triangles_skipped += count;
  scene_.report.inputs.back().triangles_skipped += count;
  tally(dropped_, count, why, object);
}

void SceneAssembly::drop_surfaces(std::int64_t count, const std::string& why, const std::string& object) {
  scene_.report.surfaces_skipped += count;
  scene_.report.inputs.back().surfaces_skipped += count;
  tally(surfaces_, count, why, object);
}

void SceneAssembly::warn(const std::string& line) { scene_.report.warnings.push_back(line); }

void SceneAssembly::end_input() {
  const std::string file = "'" + input_path() + "': ";
  auto examples = [](const Tally& t) {
    std::string s;
    for (const std::string& e : t.examples) s += (s.empty() ? " (" : ", ") + ("'" + e + "'");
    return s.empty() ? s : s + (t.objects > static_cast<std::int64_t>(t.examples.size()) ? ", ...)" : ")");
  };
  for (const auto& [why, t] : skipped_) {
    warn(file + tally_text(t.count, "object") + " skipped, " + why + examples(t));
  }
  for (const auto& [why, t] : surfaces_) {
    warn(file + tally_text(t.count, "surface") + " made no triangle, " + why + examples(t));
  }
  for (const auto& [why, t] : dropped_) {
    warn(file + tally_text(t.count, "triangle") + " dropped, " + why + examples(t));
  }
  skipped_.clear();
  dropped_.clear();
  surfaces_.clear();
  to_scene_ = nullptr;
}

double SceneAssembly::lowest_ground(const std::vector<Vec3d>& points) const {
  for (const GroundSampler& g : grounds_) {
    const double z = g(points);
    if (!std::isnan(z)) return z;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace skyview
