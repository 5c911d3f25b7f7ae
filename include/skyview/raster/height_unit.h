#pragma once
// The unit of a raster's or a point cloud's heights. Ground distances come from the CRS
// (geodesics, always in metres); heights only from what the file says about them. A raster in US
// survey feet read as metres would give every angle wrong and no error, so an unstated unit is
// taken to be the metre only where the CRS's own unit is the metre or the degree (or there is no
// CRS).
#include <string>
#include <string_view>

class GDALRasterBand;
class OGRSpatialReference;

namespace skyview {

struct HeightUnit {
  double metres = 1.0;  // metres per unit of the stored heights
  std::string source;   // what said so, for the outputs' metadata ("band unit 'ft'", ...)
};

// Metres per unit for the names GDAL and common GIS files give heights ("m", "metre", "ft",
// "US survey foot", "ftUS", ...; any case; else by the first word, as in "m asl"); 0 for a name it
// does not know.
double metres_per_height_unit(std::string_view name);

// `given` > 0 (--z-scale) wins; then the band's unit (GeoTIFF's vertical units end up there);
// then the vertical part of a compound CRS; then the metre where the CRS allows it (above). A band
// unit of "unknown" counts as none. Throws skyview::Error naming `path` for a unit it does not
// know (with no vertical CRS to say instead) or cannot assume.
HeightUnit height_unit(GDALRasterBand& band, const OGRSpatialReference* crs, double given, const std::string& path);

// Metres for heights that state no unit, where `crs` allows that: none, geographic, or in metres.
// Elsewhere (a feet CRS) throws, naming `path` and the `option` that gives the unit: raster heights
// (height_unit) and footprint height fields, which carry no unit at all.
HeightUnit unstated_height_unit(const OGRSpatialReference* crs, const std::string& path, const std::string& option);

// The same for a point cloud's z, whose x, y and z are coordinates of one CRS (LAS): `given` > 0
// wins; then the vertical part of its compound CRS (the user's --s_srs or the file's WKT); then
// `stated` > 0 (what the file says apart from its CRS: PointCloud::z_unit_metres); then its CRS's own
// unit (a LAS file in state-plane feet holds its heights in feet), the metre for a geographic CRS.
// `crs` null: the cloud's coordinates are taken to be in `output` (the DSM's CRS), and so is z.
HeightUnit cloud_height_unit(const OGRSpatialReference* crs, const OGRSpatialReference* output, double stated,
                             double given);

}  // namespace skyview
