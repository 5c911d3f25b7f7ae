#pragma once
// Writing result bands to any GDAL format. Writes are atomic: the file is built under a temporary
// name beside the target and renamed into place, so a failed or interrupted run never leaves a
// half-written output or clobbers an old one.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "skyview/raster/terrain.h"

namespace skyview {

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
  // Or a window of a band: `cols` x `rows` cells whose top-left cell is (col0, row0), row-major
  // `values` (NaN = nodata), as a tiled run writes each tile's core.
  void write_window(int index, int col0, int row0, int cols, int rows, const float* values);
  void describe(int index, const OutputBand& band);
  // Dataset-level items added to (or replacing) WriteOptions::metadata: what is known only at the
  // end of a run (edge cells summed over tiles, peak memory).
  void set_metadata(const std::map<std::string, std::string>& items);
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

}  // namespace skyview
