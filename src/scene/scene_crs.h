#pragma once
// CRSs as city models name them, and the checks a scene's CRS must pass.
#include <ogr_spatialref.h>

#include <memory>
#include <optional>
#include <string>

namespace skyview {

// Parses a CRS as files and users write it: WKT, "EPSG:n", OGC URNs and URLs (CityGML srsName,
// CityJSON referenceSystem) and the German surveying authorities' "urn:adv:crs:ETRS89_UTM32*DE_DHHN92_NH"
// (Berlin's and every German state's CityGML). Axis order is x east, y north. Throws skyview::Error
// naming `what` when nothing reads it.
OGRSpatialReference scene_crs(const std::string& text, const std::string& what);

// The CRS's name for messages ("ETRS89 / UTM zone 33N"), "none (local metres)" for an empty text.
std::string crs_display_name(const std::string& text);

// Throws unless `crs` is projected in metres: a scene's vertices are metres on the ground. For a
// geographic CRS the message names the UTM zone at (lon, lat) to give instead.
void require_projected_metres(const OGRSpatialReference& crs, const std::string& what, double lon, double lat);

struct TransformDeleter {
  void operator()(OGRCoordinateTransformation* t) const { OGRCoordinateTransformation::DestroyCT(t); }
};
using TransformPtr = std::unique_ptr<OGRCoordinateTransformation, TransformDeleter>;

// From `from` to `to`, or null where they are the same CRS. Throws naming `what` where PROJ knows no way.
TransformPtr scene_transform(const OGRSpatialReference& from, const OGRSpatialReference& to, const std::string& what);

}  // namespace skyview
