#pragma once
// What skyview asks of PCL, behind a module loaded on first use (libskyview_pcl.so, built from
// src/pcl_module/). PCL's libraries and the VTK they pull in are about 80 shared libraries; linked
// into the executable, binding them took about 0.2 s of every run's start, point clouds or not.
//
// The module and skyview are built together by one compiler, so the entry points pass standard
// library types. They throw nothing: each returns an empty string on success, or a one-line error.
#include <string>
#include <vector>

#include "skyview/las_file.h"
#include "skyview/point_filters.h"

namespace skyview::detail {

struct PclModule {
  // Bumped whenever an entry point changes, so that a stale module is refused, not called.
  static constexpr int kAbiVersion = 1;
  int abi_version = kAbiVersion;

  // Every point of a PLY (`ply`) or PCD file with finite coordinates, in file order.
  std::string (*read_cloud)(const std::string& path, bool ply, std::vector<LasPoint>& points);
  // As statistical_inliers and morphological_ground (point_filters.h), arguments already checked.
  std::string (*statistical_inliers)(const std::vector<XyzPoint>& points, int k, double sigma, std::vector<char>& keep);
  std::string (*morphological_ground)(const std::vector<XyzPoint>& points, const GroundFilterParams& params,
                                      std::vector<char>& ground);
};

// The module, loaded once per process: from $SKYVIEW_MODULE_DIR if set, else beside the running
// executable, else its ../lib/skyview, else the install folder. Throws skyview::Error (one line,
// naming the folders tried) when none holds a module of this version.
const PclModule& pcl_module();

}  // namespace skyview::detail

// The module's one exported symbol.
extern "C" const skyview::detail::PclModule* skyview_pcl_module();
