#pragma once
// Reading height rasters from, and writing result bands to, any GDAL format. Writes are
// atomic: the file is built under a temporary name beside the target and renamed into place,
// so a failed or interrupted run never leaves a half-written output or clobbers an old one.
#include <map>
#include <memory>
#include <string>
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

// One band of any raster as floats (NaN where nodata or masked), for comparing results: values as stored,
// no checks beyond the file opening and the band existing.
struct RasterBand {
  Grid<float> values;
  GeoReference georef;
  std::string description;  // GDAL's band description ("svf" in skyview's outputs), may be empty
  std::string unit;         // GDAL's unit type ("1", "degrees" in skyview's outputs), may be empty
};
RasterBand read_band(const std::string& path, int band);

struct OutputBand {
  std::string description;
  std::string unit;               // "degrees", "1" for ratios ...
  const float* values = nullptr;  // width*height, NaN = nodata
  std::map<std::string, std::string> metadata;
};

struct WriteOptions {
  std::string format = "GTiff";
  std::vector<std::string> creation_options;  // KEY=VALUE, override the defaults
  bool overwrite = false;
  float nodata = -9999.0f;
  std::map<std::string, std::string> metadata;  // dataset-level (run parameters)
  // Rows of every band BandWriter is handed at a time (0: any): GeoTIFF's default tiles are made no
  // taller, since a tile row of every band is held until it is compressed.
  int rows_at_once = 0;
};

// Writes a float32 raster a band at a time, so that a product of many bands need not be held
// whole. Nothing appears at `path` until finish(); a writer destroyed before then leaves no file.
// Throws skyview::Error if `path` exists and !overwrite, or if writing fails.
class BandWriter {
 public:
  BandWriter(const std::string& path, int width, int height, int bands, const GeoReference& georef,
             const WriteOptions& options);
  ~BandWriter();
  BandWriter(const BandWriter&) = delete;
  BandWriter& operator=(const BandWriter&) = delete;
  // Band `index` (from 0), in any order.
  void write(int index, const OutputBand& band);
  // Or a band in parts: rows [row0, row0 + rows) from `values` (rows x width, NaN = nodata), and
  // the band's description, unit and metadata (its values unused).
  void write_rows(int index, int row0, int rows, const float* values);
  void describe(int index, const OutputBand& band);
  // Rows of the format's blocks (tiles or strips): parts in multiples of them are compressed once.
  int block_rows() const;
  void finish();

 private:
  struct State;
  std::unique_ptr<State> s_;
};

// All bands at once through a BandWriter. Throws skyview::Error if `path` exists and
// !overwrite, or if writing fails.
void write_bands(const std::string& path, int width, int height, const GeoReference& georef,
                 const std::vector<OutputBand>& bands, const WriteOptions& options);

// Writes absolute heights (base + relative) as one float32 band named "height" in metres.
void write_terrain(const std::string& path, const Terrain& terrain, const WriteOptions& options);

// Writes an 8-bit PNG of `channels` (1 grey, 2 grey and alpha, 3 RGB, 4 RGBA) interleaved samples per pixel, rows
// top to bottom, through GDAL's PNG driver, under a temporary name renamed into place. Throws
// skyview::Error if `path` exists and !overwrite, or if writing fails.
void write_png(const std::string& path, int width, int height, int channels, const std::uint8_t* pixels,
               bool overwrite);

// Writes a greyscale 8-bit PNG of `values` scaled linearly from [lo, hi] to [0, 255]; where any is nodata
// (NaN) an alpha channel makes those pixels transparent.
void write_preview_png(const std::string& path, int width, int height, const float* values, double lo, double hi,
                       bool overwrite);

// Refuses early (before any computation) when an output exists and !overwrite, or exists and is
// not a regular file (a device or a folder is never replaced).
void check_output_writable(const std::string& path, bool overwrite);

// Refuses, before any computation, writing `path` in a GDAL format that cannot write `bands`
// float32 bands with these creation options (unknown, writes no file, rounds floats, refuses the
// band count, as AAIGrid does for more than one, or keeps fewer, as XYZ does): the run would
// otherwise fail, round or lose bands only at the end. Also refuses a `path` that does not end in
// an extension the format names (`out.png` written as a GeoTIFF, `svf.nc` without -of netCDF).
void check_output_format(const std::string& path, const std::string& format, int bands,
                         const std::vector<std::string>& creation_options);

// Refuses, before any computation, an output that is also an input or another output (by the
// file it names: "./a.tif", a link to it and "a.tif" are one). Empty paths are left out.
void check_outputs_apart(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs);

// Writes an output that is not a raster (a JSON or markdown report, an encoded plot) the way
// rasters are written: under a temporary name beside `path`, renamed into place once complete.
// Throws skyview::Error if `path` exists and !overwrite, or if writing fails (then nothing
// appears at `path`).
void write_output_file(const std::string& path, const std::string& bytes, bool overwrite);

}  // namespace skyview
