#pragma once
// The height raster every other command reads, built from what a city provides: a terrain
// model, LiDAR point clouds and building footprints, on one grid the user chooses.
// Combination rule: DSM = max(terrain, buildings, gridded returns), cell by cell, ignoring
// whichever is missing there.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "skyview/raster/georeference.h"
#include "skyview/core/grid.h"

namespace skyview {

struct DsmOptions {
  std::vector<std::string> dems;            // any GDAL rasters, warped bilinearly onto the grid
  std::vector<std::string> points;          // LAS, PLY, PCD or XYZ text clouds
  std::string s_srs;                        // CRS of the clouds (default: each file's own)
  std::string footprints;                   // any OGR polygon layer (first layer)
  std::string height_field;                 // building height attribute
  std::string base_field;                   // optional: absolute base height attribute
  bool absolute_heights = false;            // height_field is absolute, not above the terrain
  std::string t_srs;                        // output CRS (default: first input's)
  std::optional<std::array<double, 4>> te;  // xmin ymin xmax ymax in the output CRS
  double res = 0.0;                         // metres (CRS units); 0 = the DEM's, else 1
  std::string stat = "max";                 // max | mean | min | idw for points
  double idw_radius = 1.0;                  // cells
  double idw_power = 2.0;
  std::vector<int> classes;     // empty = all returns
  bool ground_only = false;     // class 2, or the morphological filter when unclassified
  double ground_window = 40.0;  // metres: the filter's largest window
  double ground_slope = 1.0;    // the filter's terrain slope (rise over run)
  bool denoise = false;         // statistical outlier removal before gridding
  int denoise_k = 8;            // neighbours
  double denoise_sigma = 3.0;   // standard deviations
  bool fill = false;            // close nodata holes (GDALFillNodata)
  double fill_distance = 20.0;  // cells
  double z_scale = 0.0;         // metres per DEM height unit; 0: from each DEM (height_unit.h)
  double points_z_scale = 0.0;  // metres per cloud z unit; 0: from each cloud (cloud_height_unit)
  // Metres per unit of the footprints' height fields; 0: metres, refused where the layer's CRS is in
  // another unit (attributes carry no unit, and such layers often give feet).
  double footprint_z_scale = 0.0;
  bool want_dtm = false;  // also the terrain: the DEMs, else the clouds' bare earth
};

struct DsmReport {
  std::uint64_t points_read = 0, points_used = 0, points_removed_as_noise = 0;
  std::string ground_source;  // "class 2" or "morphological filter" with --ground-only
  std::int64_t cells_from_points = 0, cells_filled = 0;
  int footprints_burned = 0, footprints_repaired = 0, footprints_skipped = 0, footprints_from_cloud = 0;
  int footprints_not_polygons = 0;        // features without a polygon (points, lines, no geometry): left out
  std::vector<std::string> height_units;  // per DEM, cloud and footprint layer with height fields
  std::vector<std::string> warnings;      // what the inputs' readers doubt (PointCloud::warnings)
};

struct DsmResult {
  GeoReference georef;
  Grid<float> dsm, dtm;  // NaN = nodata; dtm: the warped DEMs, else (with want_dtm or relative
                         // footprint heights) the clouds' ground returns, filled; else empty
  DsmReport report;
};

// Throws skyview::Error (one line) for missing or unreadable inputs, empty clouds, a vector
// without polygons, a missing height field, CRSs that cannot be related, or an empty grid.
DsmResult build_dsm(const DsmOptions& options);

}  // namespace skyview
