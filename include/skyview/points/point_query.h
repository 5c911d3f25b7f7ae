#pragma once
// `skyview points`: svf, svf_surface and sky_visibility of observers at points of a DSM, each at a
// height above the surface, found along the observer's own rays (point_horizons.h), for a table of
// points (point_table.h) written back with the results.
#include <string>
#include <vector>

#include "skyview/horizon/point_horizons.h"
#include "skyview/points/point_table.h"
#include "skyview/raster/terrain.h"

namespace skyview {

struct PointQueryOptions {
  double height = 1.1;           // metres above the surface
  PointHorizonOptions horizons;  // directions (default 64 here), method, radius, curvature ...
  bool profile = false;          // add each observer's horizon (degrees per direction) as a JSON array
};

struct PointQueryResult {
  PointHorizons horizons;
  std::vector<Observer> observers;   // one per table row (rows with a problem included)
  std::vector<PointSkyView> values;  // NaN where a row has a problem
  std::vector<std::string> problem;  // per row: the table's problem or the observer's, empty if none
  std::size_t failed = 0;
};

// The observers of `table` (its points already in the terrain's CRS, transform_points) at
// `options.height`, their horizons and sky-view values. Rows with a problem are carried along.
PointQueryResult query_points(const Terrain& terrain, const PointTable& table, const PointQueryOptions& options,
                              ProgressCounter* progress = nullptr);

// The result columns `skyview points` adds: svf, svf_surface, sky_visibility, ground_m, eye_m,
// horizon_deg (with options.profile) and error.
std::vector<ResultColumn> point_result_columns(const PointQueryResult& result, const PointQueryOptions& options);

}  // namespace skyview
