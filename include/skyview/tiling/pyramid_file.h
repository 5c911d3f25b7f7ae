#pragma once
// The far field's overview pyramid (far_field.h) on disk, so that a --tiles-dir run makes it once
// (one read of the whole raster) and its reruns, and every rank of an mpirun, take it from there.
//
// A small binary format rather than a GeoTIFF per level: the pyramid is an intermediate only
// skyview reads, its levels must come back bit for bit (NaN where a block holds no valid cell),
// and it carries what GDAL has no place for (the first level, each level's relief, the raster's
// height range, the input it was built from). All numbers are little-endian:
//
//   magic "SKYVPYRM", u32 version (2), u32 first level (1 to 30), u32 raster width, u32 raster
//   height (1 to 2^31 - 1), u32 levels (as many as halving the first level to one cell gives), u32
//   flags (bit 0: the minima follow the maxima; no other bit set), f64 lowest, f64 highest, u32
//   source length (at most 64 KiB) and its bytes (what the pyramid was built from, compared by
//   whoever reuses it), levels f64 reliefs, then each level's float32 maxima row by row (level
//   first_level: ceil(width / 2^first) x ceil(height / 2^first) cells, each next one half as many
//   per side rounded up), the minima likewise where flagged, and last the u64 FNV-1a of every byte
//   before.
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "skyview/core/grid.h"

namespace skyview {

// The levels of an OverviewPyramid as it holds them.
struct PyramidLevels {
  int first_level = 1;
  int width = 0, height = 0;     // the raster's cells
  std::vector<Grid<float>> max;  // level first_level + i's maxima (NaN where every cell below is nodata)
  std::vector<Grid<float>> min;  // the same levels' minima where kept (negative openness), else empty
  std::vector<double> relief;    // per level: the largest maximum less minimum within one cell
  double lowest = INFINITY, highest = -INFINITY;  // the raster's valid heights (relative to the base height)
};

// The file's bytes for `levels` built from `source` (any text, at most 64 KiB).
std::string encode_pyramid(const PyramidLevels& levels, const std::string& source);
// The levels and source of a pyramid file's bytes. Throws skyview::Error, one line naming `name`,
// for bytes that are not such a file or were damaged (wrong magic, version, sizes, checksum).
PyramidLevels decode_pyramid(std::string_view bytes, const std::string& name, std::string* source = nullptr);

// The same from a file (written with write_output_file(path, encode_pyramid(...), ...)). Throws
// skyview::Error naming `path`.
PyramidLevels read_pyramid_file(const std::string& path, std::string* source = nullptr);

// The checksum a pyramid file ends with (FNV-1a of every byte before it), as 16 hex digits: what a
// tile manifest records for it.
std::string pyramid_checksum(std::string_view bytes);

}  // namespace skyview
