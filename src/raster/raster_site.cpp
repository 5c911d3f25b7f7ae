// The geographic centre of a raster.
#include "skyview/raster/raster_site.h"

#include <ogr_spatialref.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "skyview/core/error.h"

namespace skyview {

std::optional<GeoPoint> raster_centre_geographic(const GeoReference& georef, int width, int height) {
  if (!georef.has_geotransform || georef.crs_wkt.empty()) return std::nullopt;
  OGRSpatialReference srs;
  if (srs.importFromWkt(georef.crs_wkt.c_str()) != OGRERR_NONE) throw Error("the raster's CRS cannot be parsed");
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRSpatialReference> geog(srs.CloneGeogCS());
  if (!geog) throw Error("the raster's CRS has no geographic coordinate system");
  geog->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> to_geog(OGRCreateCoordinateTransformation(&srs, geog.get()));
  if (!to_geog) throw Error("cannot transform the raster's CRS to geographic coordinates");
  // x_of/y_of take cell indices to cell centres: the extent's middle is (width − 1) / 2.
  double x = georef.x_of(0.5 * (width - 1), 0.5 * (height - 1)), y = georef.y_of(0.5 * (width - 1), 0.5 * (height - 1));
  if (!to_geog->Transform(1, &x, &y) || !std::isfinite(x) || !std::isfinite(y) || std::abs(y) > 90.0) {
    throw Error("the raster's centre lies outside the valid area of its CRS");
  }
  return GeoPoint{y, std::remainder(x, 360.0)};
}

double angular_distance_deg(const GeoPoint& a, const GeoPoint& b) {
  constexpr double deg = std::numbers::pi / 180.0;
  const double dlat = (b.latitude_deg - a.latitude_deg) * deg, dlon = (b.longitude_deg - a.longitude_deg) * deg;
  const double h = std::pow(std::sin(dlat / 2), 2) +
                   std::cos(a.latitude_deg * deg) * std::cos(b.latitude_deg * deg) * std::pow(std::sin(dlon / 2), 2);
  return 2.0 * std::asin(std::min(1.0, std::sqrt(h))) / deg;
}

}  // namespace skyview
