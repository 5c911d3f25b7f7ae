#pragma once
// The unit of a raster's heights. Ground distances come from the CRS (geodesics, always in
// metres); heights only from what the file says about them. A raster in US survey feet read as
// metres would give every angle wrong and no error, so an unstated unit is taken to be the metre
// only where the CRS's own unit is the metre or the degree (or there is no CRS).
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
// "US survey foot", "ftUS", ...; any case); 0 for a name it does not know.
double metres_per_height_unit(std::string_view name);

// `given` > 0 (--z-scale) wins; then the band's unit (GeoTIFF's vertical units end up there);
// then the vertical part of a compound CRS; then the metre where the CRS allows it (above).
// Throws skyview::Error naming `path` for a unit it does not know or cannot assume.
HeightUnit height_unit(GDALRasterBand& band, const OGRSpatialReference* crs, double given, const std::string& path);

}  // namespace skyview
