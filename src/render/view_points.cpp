#include "skyview/render/view_points.h"

#include <algorithm>
#include <cmath>

#include "skyview/dsm/las_file.h"

namespace skyview {

std::size_t write_view_points(const std::string& path, const ViewBuffers& view, const Scene& scene,
                              const ViewPointsOptions& options) {
  LasWriteOptions lo;
  lo.version_minor = 4;
  lo.point_format = 6;
  lo.crs_wkt = scene.crs_wkt;
  for (int k = 0; k < 3; ++k) {
    lo.scale[k] = options.scale;
    lo.offset[k] = std::round(scene.origin[k]);  // keeps a city's UTM coordinates within int32 steps
  }
  for (const ViewPointAttribute& a : options.attributes) lo.extra.push_back({a.name, a.description, {}});
  std::vector<LasPoint> points;
  points.reserve(view.hits());
  for (std::size_t i = 0; i < view.position.size(); ++i) {
    if (!view.hit(i)) continue;
    const Vec3f& p = view.position[i];
    LasPoint q{scene.origin[0] + p[0], scene.origin[1] + p[1], scene.origin[2] + p[2], 0, 1, 1, 0};
    if (options.intensity) {
      const float v = options.intensity[i];
      q.intensity = std::isnan(v) ? 0 : static_cast<std::uint16_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 65535));
    }
    points.push_back(q);
    for (std::size_t k = 0; k < options.attributes.size(); ++k)
      lo.extra[k].values.push_back(options.attributes[k].values[i]);
  }
  write_las(path, points, lo);
  return points.size();
}

}  // namespace skyview
