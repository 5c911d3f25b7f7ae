#pragma once
// A small synthetic district with what a city hands over: building footprints with heights and
// an airborne LiDAR survey of the same scene (classified ground, buildings and trees, plus a few
// birds as noise). The sample-data script writes it into sample_dems/ for the Quick start, and
// tests know every height in it.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "skyview/dsm/las_file.h"

namespace skyview {

struct DistrictBuilding {
  std::vector<std::array<double, 2>> outer, courtyard;  // rings (closed implicitly); courtyard may be empty
  double base = 0, height = 0;                          // absolute base, height above it
  bool height_known = true;                             // false: the footprint carries no height
};

struct SyntheticDistrict {
  double x0 = 0, y0 = 0, size = 0;  // south-west corner and side, metres in the CRS
  double ground_at_origin = 50.0, slope_x = 0.01;
  std::vector<DistrictBuilding> buildings;
  double ground(double x, double y) const;
  // The surface the survey sees: ground, roofs, tree crowns.
  double surface(double x, double y, int* lidar_class = nullptr) const;
};

SyntheticDistrict synthetic_district(double x0, double y0, double size, std::uint64_t seed = 1);

// Returns on a jittered lattice of `density` per square metre, classified (2 ground, 6 building,
// 5 high vegetation), with `birds` isolated returns 40-80 m up (class 1). Throws beyond
// 4294967295 returns, all a LAS 1.2 header can count.
std::vector<LasPoint> district_lidar(const SyntheticDistrict& d, double density, int birds, std::uint64_t seed = 1);

// Writes the footprints (fields: name, base, height; height null where unknown) with the OGR
// vector driver the extension names, in any case (.gpkg, .shp, else GeoJSON). The files are
// complete before they replace an old output (a shapefile with all its side files).
void write_district_footprints(const std::string& path, const SyntheticDistrict& d, const std::string& crs_wkt,
                               bool overwrite);

}  // namespace skyview
