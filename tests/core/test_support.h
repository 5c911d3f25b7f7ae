#pragma once
// Helpers shared by the core tests: analytic terrains, one-cell horizon runs, temp folders.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "skyview/horizon/horizon_engine.h"
#include "skyview/raster/raster_io.h"
#include "skyview/sky_view/sky_view.h"
#include "skyview/synthetic/synthetic.h"
#include "temp_dir.h"

#include <cpl_conv.h>
#include <ogr_spatialref.h>

namespace skyview::test {

constexpr double kDeg = M_PI / 180.0;

struct CellResult {
  double svf, svf_surface, sky_visibility, openness_positive, openness_negative;
};

// Runs `method` for the single cell (col, row) and returns its products.
// Test names of engines: a method, or "sweep2", the sweep with two far lines (--far-lines 2; one
// is the default).
inline std::string engine_method(const std::string& name, HorizonParams& p) {
  if (name != "sweep2") return name;
  p.far_lines = 2;
  return "sweep";
}

inline CellResult run_cell(const Terrain& t, int col, int row, const std::string& name, HorizonParams p) {
  const std::string method = engine_method(name, p);
  p.lower = true;
  if (method == "sweep") p.radius = 0.0;  // exact over the whole raster
  if (method == "raycast") p.rays = 0;
  auto engine = make_horizon_engine(method, p);
  HorizonField field;
  ProgressCounter progress;
  const Window w{col, row, 1, 1};
  engine->compute(t, w, field, progress);
  const SkyViewProducts out = sky_view_products(t, w, field, engine->radius(), EdgeMode::open);
  return {out.svf(0, 0), out.svf_surface(0, 0), out.sky_visibility(0, 0), out.openness_positive(0, 0),
          out.openness_negative(0, 0)};
}

// How two runs' horizons compare where the second (the reference) has one: the largest |difference|
// of horizons and lowest angles (where the reference has them, so must the first), the cells where only the
// first is NaN, and how many reference horizons stand above 0.05 rad (a test needs far terrain).
struct FieldDifference {
  double worst = 0.0;
  std::size_t nan_mismatches = 0, high = 0;
};
inline FieldDifference field_difference(const HorizonField& a, const HorizonField& reference) {
  FieldDifference d;
  for (std::size_t i = 0; i < reference.upper.size(); ++i) {
    if (std::isnan(reference.upper[i])) continue;
    d.nan_mismatches += std::isnan(a.upper[i]);
    d.worst = std::max(d.worst, std::abs(double(a.upper[i]) - reference.upper[i]));
    if (!reference.lower.empty()) d.worst = std::max(d.worst, std::abs(double(a.lower[i]) - reference.lower[i]));
    d.high += reference.upper[i] > 0.05f;
  }
  return d;
}

inline std::string wkt_of(const char* user_crs) {
  init_gdal();
  OGRSpatialReference srs;
  srs.SetFromUserInput(user_crs);
  char* wkt = nullptr;
  srs.exportToWkt(&wkt);
  std::string s = wkt;
  CPLFree(wkt);
  return s;
}

// `terrain` (rasterised on local_grid) with a CRS: a Transverse Mercator of scale 1 centred on
// the raster's centre, where grid north is true north and cells keep their size, so that runs
// behave as on local_grid, for tests whose stderr must hold nothing but what they test (a raster
// without a CRS is warned of).
inline Terrain with_local_metric_crs(Terrain terrain) {
  terrain.georef.crs_wkt = wkt_of("+proj=tmerc +lat_0=0 +lon_0=0 +k=1 +x_0=0 +y_0=0 +datum=WGS84 +units=m +no_defs");
  return terrain;
}

}  // namespace skyview::test
