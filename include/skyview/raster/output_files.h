#pragma once
// Outputs that are not result rasters (reports, plots, pictures), written as rasters are: under a
// temporary name beside the target, renamed into place once complete.
#include <cstdint>
#include <string>

namespace skyview {

// Writes an 8-bit PNG of `channels` (1 grey, 2 grey and alpha, 3 RGB, 4 RGBA) interleaved samples per pixel, rows
// top to bottom, through GDAL's PNG driver, under a temporary name renamed into place. Throws
// skyview::Error if `path` exists and !overwrite, or if writing fails.
void write_png(const std::string& path, int width, int height, int channels, const std::uint8_t* pixels,
               bool overwrite);

// Writes an output that is not a raster (a JSON or markdown report, an encoded plot) the way
// rasters are written: under a temporary name beside `path`, renamed into place once complete.
// Throws skyview::Error if `path` exists and !overwrite, or if writing fails (then nothing
// appears at `path`).
void write_output_file(const std::string& path, const std::string& bytes, bool overwrite);

}  // namespace skyview
