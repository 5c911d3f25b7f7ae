#pragma once
// The file `skyview skymap` writes: an exposure map as a raster of two float32 bands (direct and
// diffuse, Wh m-2 sr-1), azimuth in degrees along x and elevation in degrees along y (no CRS), and
// the sky's parameters, site and period as dataset metadata (sky_request.h). Reading one back
// gives the map and the request that made it, so that a command can rebuild the time steps.
#include <map>
#include <string>

#include "skyview/raster/raster_io.h"
#include "skyview/sky/exposure_map.h"
#include "skyview/sky/sky_request.h"

namespace skyview {

// Writes `map` with `metadata` (PreparedSky::metadata after make_exposure_map, plus the caller's);
// options as for write_bands.
void write_skymap(const std::string& path, const ExposureMap& map, const WriteOptions& options);

struct SkymapFile {
  ExposureMap map{1, 1};
  std::map<std::string, std::string> metadata;
  // The sky, site and period it was made for, from the metadata (FROM_UTC/TO_UTC for the period).
  SkyRequest request;
  double latitude_deg = 0.0, longitude_deg = 0.0;
};

// Throws skyview::Error (one line, naming the file) where `path` cannot be read or is not a map
// written by skyview skymap: two bands named direct and diffuse, square cells spanning 0..360
// degrees of azimuth and 90..0 of elevation, and the SKY, LATITUDE and LONGITUDE metadata.
SkymapFile read_skymap(const std::string& path);

// A map already in memory (skyview.skymap() in Python) with its metadata, checked as read_skymap
// checks a file's (`name` stands for the file in messages), and the request read from it.
SkymapFile skymap_from_bands(ExposureMap map, std::map<std::string, std::string> metadata, const std::string& name);

}  // namespace skyview
