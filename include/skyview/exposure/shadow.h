#pragma once
// Shadows at one instant (skyview shadow; docs/commands/shadow.md): whether the sun's centre, or
// which share of its disc, is seen from each cell, and the cosine of the sun on the cell's own
// surface. The horizon is found along the sun's azimuth itself (one direction, turned to it), so a
// tower's shadow ends where its top's elevation angle falls below the sun's.
#include "skyview/core/grid.h"
#include "skyview/core/progress.h"
#include "skyview/horizon/horizon_engine.h"
#include "skyview/sky/sky_model.h"
#include "skyview/sky_view/sky_view.h"

namespace skyview {

struct ShadowRequest {
  double sun_azimuth = 0.0;    // radians clockwise from north
  double sun_elevation = 0.0;  // radians, topocentric and refracted; must be above 0
  bool soft = false;           // the visible share of the disc instead of its centre
  double disc_radius = kSunAngularRadius;
  EdgeMode edge = EdgeMode::open;
};

struct ShadowBands {
  Grid<float> sunlit;         // 1 seen, 0 hidden; with `soft` the disc's visible share 0 .. 1
  Grid<float> incidence_cos;  // cosine of the sun on the cell's surface (Horn normal); < 0 behind it
  std::int64_t edge_cells = 0;
};

// The horizon parameters of `base` turned to one direction at the sun's azimuth.
HorizonParams shadow_horizon_params(HorizonParams base, double sun_azimuth);

// Shadows of the cells of `window` from `engine`, made with shadow_horizon_params for this sun.
// Throws skyview::Error for a sun at or below the horizon or an engine not turned to it.
ShadowBands compute_shadow(const HorizonEngine& engine, const Terrain& terrain, const Window& window,
                           const ShadowRequest& request, ProgressCounter& progress);

}  // namespace skyview
