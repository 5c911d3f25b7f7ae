#pragma once
// Point clouds of every supported format behind one streaming interface, so the DSM builder
// grids them all the same way: LAS 1.0-1.4 (read here, see las_file.h), PLY and PCD (read with
// PCL, which loads a whole file), and plain XYZ text (streamed).
#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "skyview/dsm/las_file.h"

namespace skyview {

class PointCloud {
 public:
  virtual ~PointCloud() = default;

  const std::string& path() const { return path_; }
  // OGC WKT, or empty when the file carries no CRS.
  const std::string& crs_wkt() const { return crs_wkt_; }
  // Metres per z unit where the file states it apart from its CRS (LAS GeoTIFF keys); 0 otherwise.
  double z_unit_metres() const { return z_unit_metres_; }
  std::uint64_t point_count() const { return point_count_; }
  // What the reader doubts but reads anyway (a LAS header that counts fewer points than follow).
  const std::vector<std::string>& warnings() const { return warnings_; }
  // Bounding box of the points (min x, min y, max x, max y) in the file's CRS.
  const double* bounds() const { return bounds_; }

  // Calls `chunk` with up to `chunk_points` points at a time, in file order. Formats without
  // classes report class 1 (unclassified); formats without returns report 1 of 1.
  virtual void read_points(const std::function<void(const std::vector<LasPoint>&)>& chunk,
                           std::size_t chunk_points = 1 << 20) const = 0;

 protected:
  explicit PointCloud(std::string path) : path_(std::move(path)) {}
  // bounds_ from the points themselves: start, include each, then settle (all 0 when none was).
  void start_bounds() {
    bounds_[0] = bounds_[1] = std::numeric_limits<double>::infinity();
    bounds_[2] = bounds_[3] = -std::numeric_limits<double>::infinity();
  }
  void include_in_bounds(double x, double y) {
    bounds_[0] = std::min(bounds_[0], x), bounds_[1] = std::min(bounds_[1], y);
    bounds_[2] = std::max(bounds_[2], x), bounds_[3] = std::max(bounds_[3], y);
  }
  void settle_bounds() {
    if (!(bounds_[0] <= bounds_[2])) bounds_[0] = bounds_[1] = bounds_[2] = bounds_[3] = 0.0;
  }
  std::string path_, crs_wkt_;
  double z_unit_metres_ = 0.0;
  std::uint64_t point_count_ = 0;
  std::vector<std::string> warnings_;
  double bounds_[4] = {0, 0, 0, 0};
};

// Opens `path` by its content (the LASF signature) or extension: .las/.laz, .ply, .pcd, and
// .xyz/.txt/.csv/.pts text. Throws skyview::Error (one line) for unknown formats, unreadable or
// corrupt files, and text lines that are not numbers.
std::unique_ptr<PointCloud> open_point_cloud(const std::string& path);

namespace detail {
// Implementations, one file each; only open_point_cloud calls them.
std::unique_ptr<PointCloud> open_las_cloud(const std::string& path);
std::unique_ptr<PointCloud> open_text_cloud(const std::string& path);
std::unique_ptr<PointCloud> open_pcl_cloud(const std::string& path, bool ply);  // .ply (else .pcd)
}  // namespace detail

}  // namespace skyview
