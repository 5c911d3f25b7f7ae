// Whole-cloud filters from PCL: statistical outlier removal and the approximate progressive
// morphological ground filter (see point_filters.h).
#include <pcl/console/print.h>
#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/segmentation/approximate_progressive_morphological_filter.h>

#include <algorithm>
#include <cmath>
#include <exception>

#include "entry_points.h"

namespace skyview::pcl_entry {
namespace {

// PCL works in float: coordinates relative to the first point keep millimetres over kilometres
// where a projected northing in float would round to half a metre.
pcl::PointCloud<pcl::PointXYZ>::Ptr to_pcl(const std::vector<XyzPoint>& points) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  cloud->resize(points.size());
  const XyzPoint o = points.empty() ? XyzPoint{0, 0, 0} : points.front();
  for (std::size_t i = 0; i < points.size(); ++i) {
    (*cloud)[i] = pcl::PointXYZ(static_cast<float>(points[i].x - o.x), static_cast<float>(points[i].y - o.y),
                                static_cast<float>(points[i].z - o.z));
  }
  return cloud;
}

std::vector<char> mask_of(const pcl::Indices& kept, std::size_t n) {
  std::vector<char> mask(n, 0);
  for (const auto i : kept) mask[static_cast<std::size_t>(i)] = 1;
  return mask;
}

// Runs `filter`, turning whatever it throws into the one-line error the entry points return.
template <class Filter>
std::string guarded(const char* what, Filter&& filter) noexcept {
  try {
    filter();
    return {};
  } catch (const std::bad_alloc&) {
    return std::string(what) + ": out of memory";
  } catch (const std::exception& e) {
    return std::string(what) + " failed: " + e.what();
  } catch (...) {
    return std::string(what) + " failed";
  }
}

}  // namespace

std::string statistical_inliers(const std::vector<XyzPoint>& points, int k, double sigma,
                                std::vector<char>& keep) noexcept {
  return guarded("the outlier filter", [&] {
    pcl::StatisticalOutlierRemoval<pcl::PointXYZ> sor;
    sor.setInputCloud(to_pcl(points));
    sor.setMeanK(k);
    sor.setStddevMulThresh(sigma);
    pcl::Indices kept;
    sor.filter(kept);
    keep = mask_of(kept, points.size());
  });
}

std::string morphological_ground(const std::vector<XyzPoint>& points, const GroundFilterParams& p,
                                 std::vector<char>& ground) noexcept {
  return guarded("the ground filter", [&] {
    pcl::ApproximateProgressiveMorphologicalFilter<pcl::PointXYZ> pmf;
    pmf.setInputCloud(to_pcl(points));
    // PCL's window is in cells: 3, 5, 9, 17, ... up to the widest building.
    pmf.setMaxWindowSize(std::max(3, static_cast<int>(std::ceil(p.max_window / p.cell))));
    pmf.setCellSize(static_cast<float>(p.cell));
    pmf.setSlope(static_cast<float>(p.slope));
    pmf.setInitialDistance(static_cast<float>(p.initial_distance));
    pmf.setMaxDistance(static_cast<float>(p.max_distance));
    pmf.setBase(2.0f);
    pmf.setExponential(true);
    pcl::Indices kept;
    pmf.extract(kept);
    ground = mask_of(kept, points.size());
  });
}

}  // namespace skyview::pcl_entry
