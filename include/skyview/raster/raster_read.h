#pragma once
// Reading height rasters and result bands from any GDAL format.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "skyview/core/grid.h"
#include "skyview/raster/terrain.h"

class GDALRasterBand;

namespace skyview {

// Registers GDAL drivers once and routes GDAL's own messages to stderr as one line each.
void init_gdal();

struct ReadOptions {
  int band = 1;
  // Metres per height unit (0.3048006096 for US survey feet); 0: from the file (height_unit.h).
  double z_scale = 0.0;
  // Undeclared NaN cells count as nodata (with a warning) instead of an error.
  bool nan_is_nodata = true;
  // The raster's CRS where it carries none or a wrong one (--s_srs: EPSG code, WKT or PROJ string).
  std::string assign_crs;
};

struct ReadReport {
  std::int64_t nodata_cells = 0;
  std::int64_t undeclared_nan_cells = 0;  // NaN where the band declares another nodata value
  std::int64_t masked_cells = 0;          // of nodata_cells, those the band's GDAL mask (alpha, .msk) marks
  bool has_nodata_value = false;
  double nodata_value = 0.0;
  double z_scale = 1.0;     // the metres per height unit applied
  std::string height_unit;  // what gave it (HeightUnit::source)
};

// A packed band (Int16 centimetres, say) holds value = raw * scale + offset: GDAL's band scale and
// offset, 1 and 0 where it states none. read_terrain and read_band unpack with it; so does
// skyview dsm after warping a DEM (the bilinear weights, summing to one, commute with it).
struct BandPacking {
  double scale = 1.0, offset = 0.0;
  bool packed() const { return scale != 1.0 || offset != 0.0; }
};
// Throws, naming band `band_index` of `path`, for a scale or offset nothing can be unpacked with.
BandPacking band_packing(GDALRasterBand& band, const std::string& path, int band_index);

// Loads one band as a Terrain. Cells are nodata where they hold the band's nodata value or NaN,
// or where the band's GDAL mask (an alpha band, a mask band or file) is 0. Throws skyview::Error (one line, naming the
// file) for a missing/unreadable file, a band out of range, a raster smaller than 2x2, an all-nodata band, infinite
// values, or a CRS that cannot give ground distances.
Terrain read_terrain(const std::string& path, const ReadOptions& options, ReadReport* report = nullptr);

// Heights already in memory (a window the tiled driver read, a NumPy array): what read_terrain
// gets from a file, and the same checks and conversion to a Terrain.
struct HeightValues {
  std::string name;  // for messages: the file, or what the caller calls the array
  int width = 0, height = 0;
  std::vector<double> values;      // row-major; NaN is nodata
  std::vector<std::uint8_t> mask;  // empty, or 0 where a cell holds no data whatever its value
  bool has_nodata = false;
  double nodata = 0.0;  // the value that marks nodata, where has_nodata
  GeoReference georef;
  double metres = 1.0;                          // metres per height unit
  std::string height_unit = "metres (stated)";  // what said so ("metres (assumed..." where nothing did)
  // The lowest and highest valid heights of the whole raster these values are a piece of (in
  // their unit, before `metres`): its base height is then the raster's, so that a piece's cells
  // hold the same floats as the whole raster's (Python's dask tiles). Default: these values'.
  std::optional<std::pair<double, double>> raster_height_range;
};
// Throws skyview::Error as read_terrain does, and for cells and heights that cannot both be
// metres (where either's unit was assumed) or a geotransform that looks like degrees without a CRS;
// warns on stderr (through GDAL's handler) of a raster without a CRS or a geotransform.
Terrain terrain_from_heights(HeightValues&& values, const ReadOptions& options, ReadReport* report = nullptr);

// The WKT of a CRS given as an EPSG code, WKT or PROJ string; throws naming `option`.
std::string crs_from_user_input(const std::string& text, const std::string& option);

// One band of any raster as floats (NaN where nodata or masked), for comparing results: values as stored,
// no checks beyond the file opening and the band existing.
struct RasterBand {
  Grid<float> values;
  GeoReference georef;
  std::string description;  // GDAL's band description ("svf" in skyview's outputs), may be empty
  std::string unit;         // GDAL's unit type ("1", "degrees" in skyview's outputs), may be empty
};
RasterBand read_band(const std::string& path, int band);
// The cells of `window` (inside the raster: the caller's job) alone, their georeference the
// window's; reads no more of the file than the window.
RasterBand read_band(const std::string& path, int band, const Window& window);

}  // namespace skyview
