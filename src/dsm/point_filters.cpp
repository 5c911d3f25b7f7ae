// The filters' argument checks; PCL runs them in the PCL module (pcl_module.h).
#include "dsm/point_filters.h"

#include "pcl_module.h"
#include "skyview/core/error.h"

namespace skyview {

std::vector<char> statistical_inliers(const std::vector<XyzPoint>& points, int k, double sigma) {
  if (k < 1) throw UsageError("--denoise-k must be at least 1");
  if (points.size() <= static_cast<std::size_t>(k)) return std::vector<char>(points.size(), 1);
  std::vector<char> keep;
  const std::string error = detail::pcl_module().statistical_inliers(points, k, sigma, keep);
  if (!error.empty()) throw Error(error);
  return keep;
}

std::vector<char> morphological_ground(const std::vector<XyzPoint>& points, const GroundFilterParams& p) {
  if (!(p.cell > 0) || !(p.max_window > 0)) throw Error("the ground filter needs a positive cell and window");
  if (points.empty()) return {};
  std::vector<char> ground;
  const std::string error = detail::pcl_module().morphological_ground(points, p, ground);
  if (!error.empty()) throw Error(error);
  return ground;
}

}  // namespace skyview
