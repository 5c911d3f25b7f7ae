#pragma once
// A VRT that mosaics rasters of the same bands (the tiles of a --tiles-dir run) into one, as QGIS
// and GDAL open it: GDAL's BuildVRT, with the tiles' band descriptions, units and metadata, and the
// run's dataset metadata. Written under a temporary name and renamed into place.
#include <map>
#include <string>
#include <vector>

namespace skyview {

// Throws skyview::Error if `path` exists and !overwrite, or if writing fails.
void write_vrt_mosaic(const std::string& path, const std::vector<std::string>& tiles,
                      const std::map<std::string, std::string>& metadata, bool overwrite);

}  // namespace skyview
