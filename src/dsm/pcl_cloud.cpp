// PLY and PCD clouds, read by the PCL module (pcl_module.h) into memory: PCL loads a whole file
// anyway, so the points are handed over at once (32 bytes each) and then served in chunks.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "pcl_module.h"
#include "skyview/core/error.h"
#include "skyview/dsm/point_cloud.h"

namespace skyview {
namespace {

class PclCloud final : public PointCloud {
 public:
  PclCloud(const std::string& path, bool ply) : PointCloud(path) {
    const std::string error = detail::pcl_module().read_cloud(path, ply, points_);
    if (!error.empty()) throw Error(error);
    // NaN coordinates are PCD's mark of a missing return (organised clouds keep their grid): left
    // out, but counted and said, not lost without a word.
    const std::size_t dropped = std::erase_if(
        points_, [](const LasPoint& p) { return !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z); });
    if (dropped > 0) {
      warnings_.push_back(std::to_string(dropped) + " of the " + std::to_string(points_.size() + dropped) +
                          " points of '" + path + "' have no finite x, y and z (a missing return) and are left out");
    }
    start_bounds();
    for (const LasPoint& p : points_) include_in_bounds(p.x, p.y);
    settle_bounds();
    point_count_ = points_.size();
  }

  void read_points(const std::function<void(const std::vector<LasPoint>&)>& chunk,
                   std::size_t chunk_points) const override {
    chunk_points = std::max<std::size_t>(1, chunk_points);  // as the LAS and text readers take 0
    std::vector<LasPoint> points;
    for (std::size_t i = 0; i < points_.size(); i += chunk_points) {
      points.assign(points_.begin() + static_cast<std::ptrdiff_t>(i),
                    points_.begin() + static_cast<std::ptrdiff_t>(std::min(points_.size(), i + chunk_points)));
      chunk(points);
    }
  }

 private:
  std::vector<LasPoint> points_;
};

}  // namespace

std::unique_ptr<PointCloud> detail::open_pcl_cloud(const std::string& path, bool ply) {
  if (!std::filesystem::exists(path)) throw Error("cannot open '" + path + "': no such file or not readable");
  return std::make_unique<PclCloud>(path, ply);
}

}  // namespace skyview
