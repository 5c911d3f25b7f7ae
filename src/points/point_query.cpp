// Point queries: table rows to observers (pixel positions in the terrain), their horizons and the
// sky-view values written back.
#include "skyview/points/point_query.h"

#include <gdal.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"

namespace skyview {

PointQueryResult query_points(const Terrain& terrain, const PointTable& table, const PointQueryOptions& options,
                              ProgressCounter* progress) {
  if (!(options.height >= 0.0) || std::isinf(options.height)) throw Error("--height must be 0 or more metres");
  PointQueryResult r;
  double inverse[6];
  if (!GDALInvGeoTransform(const_cast<double*>(terrain.georef.geotransform.data()), inverse))
    throw Error("the raster's geotransform cannot be inverted");
  const std::size_t n = table.rows.size();
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  for (const PointRow& row : table.rows) {
    // GDAL's pixel/line of the point; cell centres sit at whole numbers plus a half.
    const double px = inverse[0] + row.x * inverse[1] + row.y * inverse[2];
    const double py = inverse[3] + row.x * inverse[4] + row.y * inverse[5];
    const bool ok = row.problem.empty();
    r.observers.push_back(
        {ok ? px - 0.5 - terrain.origin_col : kNaN, ok ? py - 0.5 - terrain.origin_row : kNaN, options.height});
  }
  r.horizons = point_horizons(terrain, r.observers, options.horizons, progress);
  r.values.assign(n, {kNaN, kNaN, kNaN});
  r.problem.assign(n, {});
  for (std::size_t i = 0; i < n; ++i) {
    r.problem[i] = !table.rows[i].problem.empty()   ? table.rows[i].problem
                   : !r.horizons.problem[i].empty() ? "point (" + number_text(table.rows[i].x) + ", " +
                                                          number_text(table.rows[i].y) + ") is " + r.horizons.problem[i]
                                                    : "";
    if (!r.problem[i].empty()) {
      ++r.failed;
      continue;
    }
    r.values[i] =
        point_sky_view(terrain, r.observers[i], r.horizons.of(i), r.horizons.directions, r.horizons.sector_rotation);
  }
  return r;
}

std::vector<ResultColumn> point_result_columns(const PointQueryResult& r, const PointQueryOptions& options) {
  const std::size_t n = r.values.size();
  ResultColumn svf{"svf", {}, {}}, surface{"svf_surface", {}, {}}, visibility{"sky_visibility", {}, {}};
  ResultColumn ground{"ground_m", {}, {}}, eye{"eye_m", {}, {}};
  ResultColumn profile{"horizon_deg", {}, {}}, error{"error", {}, {}};
  for (std::size_t i = 0; i < n; ++i) {
    svf.numbers.push_back(r.values[i].svf);
    surface.numbers.push_back(r.values[i].svf_surface);
    visibility.numbers.push_back(r.values[i].sky_visibility);
    const bool ok = r.problem[i].empty();
    ground.numbers.push_back(ok ? r.horizons.ground[i] : std::numeric_limits<double>::quiet_NaN());
    eye.numbers.push_back(ok ? r.horizons.eye[i] : std::numeric_limits<double>::quiet_NaN());
    error.texts.push_back(r.problem[i]);
    if (options.profile) {
      std::string json;
      if (ok) {
        json = "[";
        char buf[32];
        for (int k = 0; k < r.horizons.directions; ++k) {
          std::snprintf(buf, sizeof buf, "%s%.2f", k ? "," : "", r.horizons.of(i)[k] * 180.0 / M_PI);
          json += buf;
        }
        json += "]";
      }
      profile.texts.push_back(json);
    }
  }
  std::vector<ResultColumn> out{svf, surface, visibility, ground, eye};
  if (options.profile) out.push_back(profile);
  out.push_back(error);
  return out;
}

}  // namespace skyview
