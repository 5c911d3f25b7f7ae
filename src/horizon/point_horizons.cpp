// Point queries: observers at any position and height, their horizons along their own rays by the
// march's walk or the ray cast, on the buffer extended at the raster's edges as every raster method
// reads it (HorizonEngine::compute).
#include "skyview/horizon/point_horizons.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "earth_curvature.h"
#include "methods.h"
#include "skyview/core/error.h"
#include "skyview/horizon/surface_mesh.h"
#include "skyview/sky_view/sky_view.h"

namespace skyview {

namespace {

void check_options(const PointHorizonOptions& o) {
  const HorizonParams& p = o.params;
  if (p.directions < 1 || p.directions > 65536) throw Error("--directions must be between 1 and 65536");
  if (!(p.radius >= 0.0) || std::isinf(p.radius)) throw Error("--radius must be a positive number of metres");
  if (p.spacing != AzimuthSpacing::uniform) throw Error("point queries use uniform directions");
  if (o.method != "march" && o.method != "raycast")
    throw Error("unknown point method '" + o.method + "' (known: march, raycast)");
  if (o.method == "raycast") {
    if (p.curvature == "on") throw Error("--method raycast models no Earth curvature; use --curvature off");
    if (o.rising_steps) throw Error("rising steps come from the march only");
  }
}

}  // namespace

PointHorizons point_horizons(const Terrain& terrain, const std::vector<Observer>& observers,
                             const PointHorizonOptions& options, ProgressCounter* progress) {
  check_options(options);
  const HorizonParams& p = options.params;
  Window inner;
  const Terrain extended = extend_at_raster_edges(terrain, Window::whole(terrain), inner);
  PointHorizons out;
  out.directions = p.directions;
  out.sector_rotation = direction_set_rotation(p.azimuth_origin, terrain);
  out.reach = p.radius > 0.0 ? p.radius : ground_diagonal(extended);
  const double radius = p.radius > 0.0 ? p.radius : std::numeric_limits<double>::infinity();
  out.curvature =
      options.method == "raycast" ? 0.0 : detail::curvature_coefficient(p, out.reach, terrain.frame.earth_radius());
  const std::size_t n = observers.size();
  out.problem.assign(n, {});
  out.ground.assign(n, std::numeric_limits<double>::quiet_NaN());
  out.eye.assign(n, std::numeric_limits<double>::quiet_NaN());
  std::vector<detail::EyePoint> eyes(n);
  // The raster covers half a cell beyond its outer cell centres; the ring extend_at_raster_edges
  // adds carries the surface there, and every track ends there (track_box.h).
  const double lo_col = -0.5, hi_col = terrain.raster_width() - 0.5 - terrain.origin_col;
  const double lo_row = -0.5, hi_row = terrain.raster_height() - 0.5 - terrain.origin_row;
  for (std::size_t i = 0; i < n; ++i) {
    const Observer& o = observers[i];
    detail::EyePoint& e = eyes[i];
    e.z = std::numeric_limits<double>::quiet_NaN();
    if (!(o.height >= 0.0) || std::isinf(o.height)) throw Error("the observer's height must be 0 or more metres");
    // On the surface the ray cast's eye would start inside its own triangle (a cell's eye is on a
    // vertex, whose triangles it ignores; a point's is not).
    if (options.method == "raycast" && !(o.height > 0.0))
      throw Error("the ray cast needs observers above the surface (a height above 0)");
    e.col = o.col + inner.col0;
    e.row = o.row + inner.row0;
    if (!(o.col >= lo_col && o.col <= hi_col && o.row >= lo_row && o.row <= hi_row) ||
        !(e.col >= 0.0 && e.row >= 0.0 && e.col <= extended.width() - 1 && e.row <= extended.height() - 1)) {
      out.problem[i] = "outside the raster";
      continue;
    }
    const double ground = surface_height(extended, e.col, e.row);
    if (std::isnan(ground)) {
      out.problem[i] = "on nodata";
      continue;
    }
    e.z = ground + o.height;
    out.ground[i] = extended.base_height + ground;
    out.eye[i] = extended.base_height + e.z;
  }
  if (progress) progress->set_total(n);
  if (options.method == "raycast") {
    detail::raycast_point_horizons(extended, eyes, p.directions, out.sector_rotation, radius, out.upper, progress);
  } else {
    detail::march_point_horizons(extended, eyes, p.directions, out.sector_rotation, radius, out.curvature, p.early_exit,
                                 out.upper, options.rising_steps ? &out.rising : nullptr, progress);
  }
  return out;
}

PointSkyView point_sky_view(const Terrain& terrain, const Observer& observer, const float* horizons, int n,
                            double rotation) {
  PointSkyView v;
  v.svf = svf_horizontal(horizons, n);
  v.sky_visibility = sky_visibility(horizons, n);
  const int col = std::clamp(static_cast<int>(std::lround(observer.col)), 0, terrain.width() - 1);
  const int row = std::clamp(static_cast<int>(std::lround(observer.row)), 0, terrain.height() - 1);
  double slope = 0.0, aspect = 0.0;
  if (terrain.valid(col, row)) horn_slope_aspect(terrain, col, row, slope, aspect);
  v.svf_surface = svf_tilted(horizons, n, rotation, slope, aspect);
  return v;
}

}  // namespace skyview
