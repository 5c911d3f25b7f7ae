#pragma once
// Reading a height raster by windows, for rasters too large to hold whole (tiled runs): the raster
// is scanned once a strip of rows at a time for what every window must share (the base height its
// heights are stored relative to, its ground frame) and what read_terrain checks and reports; then
// any window is read through GDAL alone. A window's heights are the very floats read_terrain gives
// for those cells, so horizons computed on a window plus its halo equal the whole raster's.
#include <memory>
#include <string>

#include "skyview/raster/raster_read.h"
#include "skyview/raster/terrain.h"

namespace skyview {

// Width and height of `path` (any GDAL raster), opened but not read. Throws skyview::Error as
// read_terrain does for a file that does not open or lacks band `band`.
struct RasterSize {
  int width = 0, height = 0;
};
RasterSize raster_size(const std::string& path, int band = 1);

class TerrainReader {
 public:
  // Throws skyview::Error as read_terrain does (an unreadable file, only nodata, units that cannot
  // both be metres ...); `report` receives what read_terrain's would.
  TerrainReader(const std::string& path, const ReadOptions& options, ReadReport* report = nullptr);
  ~TerrainReader();
  TerrainReader(const TerrainReader&) = delete;
  TerrainReader& operator=(const TerrainReader&) = delete;

  int width() const;
  int height() const;
  const GeoReference& georef() const;
  const GroundFrame& frame() const;
  double base_height() const;
  // `window` (clipped to nothing outside the raster: the caller's job) as a Terrain placed in the
  // raster (origin, full size). Throws skyview::Error when GDAL cannot read it.
  Terrain read(const Window& window) const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace skyview
