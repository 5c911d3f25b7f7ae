#pragma once
// What skyview asks of PCL, behind a module loaded on first use (libskyview_pcl.so, built from
// src/dsm/pcl_module/). PCL's libraries and the VTK they pull in are 57 shared libraries that skyview
// needs nowhere else; linked into the executable, binding them took about 0.2 s of every run's
// start, point clouds or not.
//
// The module and skyview are built together by one compiler, so the entry points pass standard
// library types. They throw nothing: each returns an empty string on success, or a one-line error.
#include <cstddef>
#include <string>
#include <vector>

#include "skyview/dsm/las_file.h"
#include "dsm/point_filters.h"

namespace skyview::detail {

// What a module reports of the build it came from: a module from another build (an older install)
// is refused unless all of it agrees. kAbiVersion is bumped whenever an entry point changes; the
// sizes catch a structure that changed without it.
struct PclModuleBuild {
  static constexpr int kAbiVersion = 1;
  int abi_version = kAbiVersion;
  std::size_t las_point = sizeof(LasPoint), xyz_point = sizeof(XyzPoint), ground_params = sizeof(GroundFilterParams);
  bool operator==(const PclModuleBuild&) const = default;
};

struct PclModule {
  PclModuleBuild build;
  // Every point of a PLY (`ply`) or PCD file with finite coordinates, in file order.
  std::string (*read_cloud)(const std::string& path, bool ply, std::vector<LasPoint>& points) noexcept;
  // As statistical_inliers and morphological_ground (point_filters.h), arguments already checked.
  std::string (*statistical_inliers)(const std::vector<XyzPoint>& points, int k, double sigma,
                                     std::vector<char>& keep) noexcept;
  std::string (*morphological_ground)(const std::vector<XyzPoint>& points, const GroundFilterParams& params,
                                      std::vector<char>& ground) noexcept;
};

// The module, loaded once per process: only from $SKYVIEW_MODULE_DIR if that is set; else beside
// the running executable, then in its ../lib/skyview, then in the install folder. Throws
// skyview::Error (one line, naming the folders tried or the file that failed) when none holds a
// module of this build.
const PclModule& pcl_module();

}  // namespace skyview::detail

// The module's one exported symbol.
extern "C" const skyview::detail::PclModule* skyview_pcl_module();
