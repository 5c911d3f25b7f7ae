#include "skyview/dsm/point_cloud.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "skyview/core/error.h"
#include "skyview/core/lowercase.h"

namespace skyview {

namespace {

class LasCloud final : public PointCloud {
 public:
  explicit LasCloud(const std::string& path) : PointCloud(path), reader_(LasReader::open_file(path)) {
    const LasHeader& h = reader_.header();
    crs_wkt_ = h.crs_wkt;
    z_unit_metres_ = h.z_unit_metres;
    point_count_ = h.point_count;
    if (h.records_beyond_count > 0) {
      warnings_.push_back("'" + path + "' holds " + std::to_string(h.records_beyond_count) +
                          " more point records' worth of bytes after the " + std::to_string(h.point_count) +
                          " points its header counts; only those are read");
    }
    // The bounds from the points, not the header's min and max: writers leave those stale (a grid
    // from them dropped half a cloud without a word) or raw (simple1_3.las, a LAS sample, holds its
    // unscaled integers there). One more pass over the file, as the text clouds make.
    start_bounds();
    reader_.read_points([this](const std::vector<LasPoint>& points) {
      for (const LasPoint& p : points) include_in_bounds(p.x, p.y);
    });
    settle_bounds();
  }
  void read_points(const std::function<void(const std::vector<LasPoint>&)>& chunk,
                   std::size_t chunk_points) const override {
    reader_.read_points(chunk, chunk_points);
  }

 private:
  LasReader reader_;
};

}  // namespace

std::unique_ptr<PointCloud> detail::open_las_cloud(const std::string& path) { return std::make_unique<LasCloud>(path); }

std::unique_ptr<PointCloud> open_point_cloud(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open '" + path + "': no such file or not readable");
  char magic[4] = {};
  in.read(magic, 4);
  const std::string ext = lowercase_extension(path);
  if (std::memcmp(magic, "LASF", 4) == 0 || ext == ".las" || ext == ".laz") return detail::open_las_cloud(path);
  if (ext == ".ply" || ext == ".pcd") return detail::open_pcl_cloud(path, ext == ".ply");
  if (ext == ".xyz" || ext == ".txt" || ext == ".csv" || ext == ".pts") return detail::open_text_cloud(path);
  throw Error("'" + path + "': unknown point cloud format (supported: .las, .ply, .pcd, .xyz/.txt/.csv/.pts text)");
}

}  // namespace skyview
