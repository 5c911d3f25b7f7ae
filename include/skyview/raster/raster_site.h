#pragma once
// Where on the Earth a raster lies, for what needs a latitude and longitude (the sun's position).
#include <optional>

#include "skyview/raster/georeference.h"

namespace skyview {

struct GeoPoint {
  double latitude_deg = 0.0, longitude_deg = 0.0;
};

// The geographic position of the middle of a raster of width × height cells (the centre of its
// extent), from its CRS; nullopt where it has no geotransform or no CRS. Throws skyview::Error
// where the CRS cannot be read or transformed.
std::optional<GeoPoint> raster_centre_geographic(const GeoReference& georef, int width, int height);

// The great-circle distance between two points in degrees of arc.
double angular_distance_deg(const GeoPoint& a, const GeoPoint& b);

}  // namespace skyview
