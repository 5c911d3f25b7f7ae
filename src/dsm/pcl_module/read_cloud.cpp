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
#include <exception>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "entry_points.h"

namespace skyview::pcl_entry {
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

// PCL 1.13's PCD reader crashes on an empty file and on a header without its FIELDS (fixed
// upstream after Debian's release): a PCD's header must name its fields, their sizes and types,
// its width, point count and data encoding, in text lines before the data, or it is not read.
bool pcd_header_complete(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  bool fields = false, size = false, type = false, width = false, points = false;
  for (int n = 0; n < 64 && std::getline(in, line); ++n) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "FIELDS") fields = true;
    if (key == "SIZE") size = true;
    if (key == "TYPE") type = true;
    if (key == "WIDTH") width = true;
    if (key == "POINTS") points = true;
    if (key == "DATA") {
      std::string encoding;
      words >> encoding;
      const bool known = encoding == "ascii" || encoding == "binary" || encoding == "binary_compressed";
      return known && fields && size && type && width && points;
    }
  }
  return false;
}

std::string read(const std::string& path, bool ply, std::vector<LasPoint>& points) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);  // skyview's own one-line errors instead
  if (!ply && !pcd_header_complete(path))
    return "'" + path + "' is not a readable PCD point cloud (no complete header: FIELDS, SIZE, TYPE, WIDTH, " +
           "POINTS and DATA lines)";
  pcl::PCLPointCloud2 cloud;
  const int rc = ply ? pcl::io::loadPLYFile(path, cloud) : pcl::io::loadPCDFile(path, cloud);
  if (rc < 0) return "'" + path + "' is not a readable " + (ply ? "PLY" : "PCD") + " point cloud";
  int x = -1, y = -1, z = -1, cls = -1;
  for (const auto& f : cloud.fields) {
    int* slot = nullptr;
    if (f.name == "x") slot = &x;
    if (f.name == "y") slot = &y;
    if (f.name == "z") slot = &z;
    if (f.name == "classification" || f.name == "class" || f.name == "label") slot = &cls;
    if (slot && *slot < 0) *slot = static_cast<int>(&f - cloud.fields.data());
  }
  if (x < 0 || y < 0 || z < 0) return "'" + path + "' has no x, y and z fields";
  for (int i : {x, y, z, cls}) {
    if (i < 0) continue;
    const pcl::PCLPointField& f = cloud.fields[static_cast<std::size_t>(i)];
    if (f.offset + pcl::getFieldSize(f.datatype) > cloud.point_step)
      return "'" + path + "' has a field outside its point record";
  }
  const std::size_t n = static_cast<std::size_t>(cloud.width) * cloud.height;
  if (cloud.data.size() < n * cloud.point_step) return "'" + path + "' is truncated";
  points.clear();
  points.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t* rec = cloud.data.data() + i * cloud.point_step;
    auto value = [&](int f) {
      const auto& field = cloud.fields[static_cast<std::size_t>(f)];
      return field_value(rec + field.offset, field.datatype);
    };
    LasPoint p{value(x), value(y), value(z), 0, 1, 1, 1};  // non-finite ones are counted and left out by the caller
    if (cls >= 0) {
      const double c = value(cls);
      if (c >= 0 && c <= 255) p.classification = static_cast<std::uint8_t>(c);
    }
    points.push_back(p);
  }
  return {};
}

}  // namespace

std::string read_cloud(const std::string& path, bool ply, std::vector<LasPoint>& points) noexcept {
  auto unreadable = [&] { return "'" + path + "' is not a readable " + (ply ? "PLY" : "PCD") + " point cloud"; };
  try {
    return read(path, ply, points);
  } catch (const std::bad_alloc&) {
    return "'" + path + "' does not fit in memory";
  } catch (const std::exception& e) {
    return unreadable() + " (" + e.what() + ")";
  } catch (...) {
    return unreadable();
  }
}

}  // namespace skyview::pcl_entry
