// PLY and PCD clouds through PCL's readers (binary and ASCII). PCL loads a whole file into a
// PCLPointCloud2; its fields are read with their stored types, so double-precision projected
// coordinates keep their precision (PCL's float PointXYZ would round a UTM northing to 0.5 m).
// A class comes from a "classification", "class" or "label" field when the file has one.
#include <pcl/PCLPointCloud2.h>
#include <pcl/common/io.h>
#include <pcl/console/print.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "skyview/error.h"
#include "skyview/point_cloud.h"

namespace skyview {
namespace {

double field_value(const std::uint8_t* p, std::uint8_t type) {
  auto get = [p](auto v) {
    std::memcpy(&v, p, sizeof v);
    return static_cast<double>(v);
  };
  switch (type) {
    case pcl::PCLPointField::INT8:
      return get(std::int8_t{});
    case pcl::PCLPointField::UINT8:
      return get(std::uint8_t{});
    case pcl::PCLPointField::INT16:
      return get(std::int16_t{});
    case pcl::PCLPointField::UINT16:
      return get(std::uint16_t{});
    case pcl::PCLPointField::INT32:
      return get(std::int32_t{});
    case pcl::PCLPointField::UINT32:
      return get(std::uint32_t{});
    case pcl::PCLPointField::FLOAT32:
      return get(float{});
    case pcl::PCLPointField::FLOAT64:
      return get(double{});
    default:
      return std::numeric_limits<double>::quiet_NaN();
  }
}

class PclCloud final : public PointCloud {
 public:
  explicit PclCloud(const std::string& path) : PointCloud(path) {
    pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);  // our own one-line errors instead
    // open_point_cloud only sends .ply and .pcd here, in any letter case.
    const std::string ext = std::filesystem::path(path).extension().string();
    const bool ply = ext.size() == 4 && (ext[1] | 0x20) == 'p' && (ext[2] | 0x20) == 'l' && (ext[3] | 0x20) == 'y';
    const int rc = ply ? pcl::io::loadPLYFile(path, cloud_) : pcl::io::loadPCDFile(path, cloud_);
    if (rc < 0) throw Error("'" + path + "' is not a readable " + (ply ? "PLY" : "PCD") + " point cloud");
    for (const auto& f : cloud_.fields) {
      int* slot = nullptr;
      if (f.name == "x") slot = &x_;
      if (f.name == "y") slot = &y_;
      if (f.name == "z") slot = &z_;
      if (f.name == "classification" || f.name == "class" || f.name == "label") slot = &cls_;
      if (slot && *slot < 0) *slot = static_cast<int>(&f - cloud_.fields.data());
    }
    if (x_ < 0 || y_ < 0 || z_ < 0) throw Error("'" + path + "' has no x, y and z fields");
    for (int i : {x_, y_, z_, cls_}) {
      if (i >= 0 && cloud_.fields[static_cast<std::size_t>(i)].offset +
                            pcl::getFieldSize(cloud_.fields[static_cast<std::size_t>(i)].datatype) >
                        cloud_.point_step) {
        throw Error("'" + path + "' has a field outside its point record");
      }
    }
    const std::size_t n = static_cast<std::size_t>(cloud_.width) * cloud_.height;
    if (cloud_.data.size() < n * cloud_.point_step) throw Error("'" + path + "' is truncated");
    start_bounds();
    for (std::size_t i = 0; i < n; ++i) {
      const LasPoint p = point(i);
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;  // PCD's NaN = no return
      include_in_bounds(p.x, p.y);
      ++point_count_;
    }
    settle_bounds();
  }

  void read_points(const std::function<void(const std::vector<LasPoint>&)>& chunk,
                   std::size_t chunk_points) const override {
    const std::size_t n = static_cast<std::size_t>(cloud_.width) * cloud_.height;
    std::vector<LasPoint> points;
    for (std::size_t i = 0; i < n; ++i) {
      const LasPoint p = point(i);
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
      points.push_back(p);
      if (points.size() >= chunk_points) {
        chunk(points);
        points.clear();
      }
    }
    if (!points.empty()) chunk(points);
  }

 private:
  LasPoint point(std::size_t i) const {
    const std::uint8_t* rec = cloud_.data.data() + i * cloud_.point_step;
    auto value = [&](int f) {
      const auto& field = cloud_.fields[static_cast<std::size_t>(f)];
      return field_value(rec + field.offset, field.datatype);
    };
    LasPoint p{value(x_), value(y_), value(z_), 0, 1, 1, 1};
    if (cls_ >= 0) {
      const double c = value(cls_);
      if (c >= 0 && c <= 255) p.classification = static_cast<std::uint8_t>(c);
    }
    return p;
  }

  pcl::PCLPointCloud2 cloud_;
  int x_ = -1, y_ = -1, z_ = -1, cls_ = -1;
};

}  // namespace

std::unique_ptr<PointCloud> detail::open_pcl_cloud(const std::string& path) {
  if (!std::filesystem::exists(path)) throw Error("cannot open '" + path + "': no such file or not readable");
  return std::make_unique<PclCloud>(path);
}

}  // namespace skyview
