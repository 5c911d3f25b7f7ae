#pragma once
// The PCL module's entry points (see src/dsm/pcl_module.h for their contract), one file
// each; module.cpp exports them as one table.
#include "dsm/pcl_module.h"

namespace skyview::pcl_entry {

std::string read_cloud(const std::string& path, bool ply, std::vector<LasPoint>& points) noexcept;
std::string statistical_inliers(const std::vector<XyzPoint>& points, int k, double sigma,
                                std::vector<char>& keep) noexcept;
std::string morphological_ground(const std::vector<XyzPoint>& points, const GroundFilterParams& params,
                                 std::vector<char>& ground) noexcept;

}  // namespace skyview::pcl_entry
