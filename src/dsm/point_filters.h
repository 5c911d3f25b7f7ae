#pragma once
// Whole-cloud filters from PCL, for clouds held in memory: statistical outlier removal (birds,
// multipath spikes) and the progressive morphological ground filter (bare earth from an
// unclassified cloud).
#include <vector>

namespace skyview {

struct XyzPoint {
  double x, y, z;
};

// PCL's StatisticalOutlierRemoval: a point is an outlier when its mean distance to its `k`
// nearest neighbours exceeds the cloud's mean of that distance by more than `sigma` standard
// deviations. Returns 1 for the points to keep.
std::vector<char> statistical_inliers(const std::vector<XyzPoint>& points, int k, double sigma);

struct GroundFilterParams {
  double cell = 1.0;              // metres; the output grid's resolution
  double max_window = 40.0;       // metres; wider than the widest building
  double slope = 1.0;             // terrain slope allowed (rise over run)
  double initial_distance = 0.5;  // metres above the opened surface still ground
  double max_distance = 3.0;      // metres; cap of the height threshold
};

// Zhang et al. (2003), "A progressive morphological filter for removing nonground measurements
// from airborne LIDAR data", IEEE TGRS 41(4), as PCL's grid-based approximate version.
// Returns 1 for ground points.
std::vector<char> morphological_ground(const std::vector<XyzPoint>& points, const GroundFilterParams& params);

}  // namespace skyview
