#pragma once
// What the whole-raster reader (raster_read.cpp) and the windowed one (terrain_reader.cpp) share:
// a band opened with the checks every reader makes, a window of it read as doubles (unpacked, its
// mask beside), the raster's georeference, and the conversion of raw values to metres with the
// counts and checks that read_terrain reports.
#include <gdal_priv.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "raster/gdal_common.h"
#include "skyview/raster/ground_frame.h"
#include "skyview/raster/height_unit.h"
#include "skyview/raster/raster_read.h"
#include "skyview/raster/terrain.h"

namespace skyview::detail {

// Band `band_index` (from 1) of `path` opened read-only; throws skyview::Error naming the file for a
// missing or unreadable file, a folder, or a band that does not exist.
DatasetPtr open_raster_band(const std::string& path, int band_index);

// A window of one band as doubles, unpacked (BandPacking; packed nodata becomes NaN).
struct RawWindow {
  int width = 0, height = 0;
  std::vector<double> values;
  int has_nodata = 0;
  double nodata = 0;
  // The band's mask where it is not just the nodata value (an alpha band, a .msk file, a GeoTIFF's
  // internal mask): 0 marks a cell without data, whatever its value. Empty when every cell is valid
  // or the nodata value alone says which are not.
  std::vector<std::uint8_t> mask;
  bool masked(std::size_t i) const { return !mask.empty() && mask[i] == 0; }
};
// Throws skyview::Error naming the file when GDAL cannot read it.
void read_raw_window(GDALDataset& ds, int band_index, const std::string& path, const Window& window, RawWindow& out);

GeoReference georeference_of(GDALDataset& ds);

// Heights converted in place: nodata (masked, the nodata value, NaN) to NaN, the rest to metres,
// counted as ReadReport counts them, with their range.
struct HeightScan {
  ReadReport counts;
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
};
// `window` places the values in the raster, for messages naming a cell. Throws skyview::Error for
// an infinite height, or NaN where the nodata value is not NaN and !options.nan_is_nodata.
void convert_heights(std::vector<double>& values, const std::vector<std::uint8_t>& mask, bool has_nodata, double nodata,
                     double metres, const ReadOptions& options, const std::string& path, const Window& window,
                     HeightScan& scan);

// The checks on a whole raster's heights once scanned: some data, a plausible height span.
void check_height_range(const std::string& path, const HeightScan& scan, std::int64_t cells, int band);

// The ground frame of a raster's georeference; throws skyview::Error naming `path` for a
// degenerate geotransform, a CRS without one, or a CRS that cannot give ground distances.
GroundFrame checked_frame(const std::string& path, const GeoReference& georef, int width, int height);

// The unit of the band's heights (height_unit), with --s_srs (options.assign_crs) replacing the
// file's CRS in `georef` first.
HeightUnit band_height_unit(GDALDataset& ds, const ReadOptions& options, const std::string& path, GeoReference& georef);

// Cells whose ground size and heights cannot both be metres are refused where either's unit was
// assumed; a raster without a CRS or a geotransform is warned of.
void check_units(const std::string& name, const GeoReference& georef, int width, int height, const GroundFrame& frame,
                 double relief, const std::string& height_unit);

}  // namespace skyview::detail
