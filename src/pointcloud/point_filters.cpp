#include "skyview/point_filters.h"

#include <pcl/console/print.h>
#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/segmentation/approximate_progressive_morphological_filter.h>

#include <algorithm>
#include <cmath>

#include "skyview/error.h"

namespace skyview {
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

}  // namespace

std::vector<char> statistical_inliers(const std::vector<XyzPoint>& points, int k, double sigma) {
  if (k < 1) throw Error("--denoise-k must be at least 1");
  if (points.size() <= static_cast<std::size_t>(k)) return std::vector<char>(points.size(), 1);
  pcl::StatisticalOutlierRemoval<pcl::PointXYZ> sor;
  sor.setInputCloud(to_pcl(points));
  sor.setMeanK(k);
  sor.setStddevMulThresh(sigma);
  pcl::Indices kept;
  sor.filter(kept);
  return mask_of(kept, points.size());
}

std::vector<char> morphological_ground(const std::vector<XyzPoint>& points, const GroundFilterParams& p) {
  if (!(p.cell > 0) || !(p.max_window > 0)) throw Error("the ground filter needs a positive cell and window");
  if (points.empty()) return {};
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
  pcl::Indices ground;
  pmf.extract(ground);
  return mask_of(ground, points.size());
}

}  // namespace skyview
