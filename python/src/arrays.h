#pragma once
// NumPy arrays in and out of the library: heights with their georeference as a Terrain (the same
// checks and conversion as a raster read from a file), and results handed to NumPy without a copy.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "skyview/core/thread_limit.h"
#include "skyview/raster/terrain.h"

namespace skyview::python {

namespace py = pybind11;

// Where a height array sits and what its values mean, as the Python functions take it.
struct ArrayGeoreference {
  std::optional<double> cell_size;               // metres, square cells, north up
  std::optional<std::vector<double>> transform;  // GDAL/rasterio affine: 6 numbers, GDAL order
  std::optional<std::string> crs;                // anything GDAL/PROJ reads (EPSG:25833, WKT, PROJ)
  std::optional<double> nodata;                  // the value that marks nodata (NaN always does)
  std::optional<double> z_scale;                 // metres per height unit; default as for a raster
  // A tile of a larger raster (skyview.dask): its first column and row in that raster and the
  // raster's width and height; `transform` or `cell_size` is then the whole raster's. Tiles so
  // placed share the raster's ground frame, edges, direction set and seeds (terrain.h), so that
  // their cells get the whole raster's values wherever the halo holds their search radius.
  std::optional<std::array<int, 4>> tile;
  // With `tile`: the whole raster's lowest and highest valid heights (in z's unit), so that the
  // tile's heights are stored relative to the raster's base height and give its very bits.
  std::optional<std::array<double, 2>> height_range;
};

// Throws skyview::Error (one line) for an array that is not 2-D, of a type that holds no heights
// (bool, complex, text, objects), empty, or too small, for a cell size that is not a positive
// finite number, a transform that is not 6 finite numbers, and whatever read_terrain refuses.
// Warnings (no CRS, say) are appended to `warnings`.
Terrain terrain_from_array(const py::handle& z, const ArrayGeoreference& where, std::vector<std::string>& warnings);

// A row-major float array of `shape`, owning `values` (moved, not copied).
py::array_t<float> to_numpy(std::vector<float>&& values, const std::vector<py::ssize_t>& shape);

// Issues each line as a Python warning (UserWarning, as GDAL's own bindings do).
void warn_all(const std::vector<std::string>& warnings);

// While alive, GDAL's warnings and errors go to `lines` instead of stderr (GDAL's handler is
// per thread when pushed; the library's reads and CRS checks run on the calling thread).
class CollectGdalMessages {
 public:
  explicit CollectGdalMessages(std::vector<std::string>& lines);
  ~CollectGdalMessages();
  CollectGdalMessages(const CollectGdalMessages&) = delete;
  CollectGdalMessages& operator=(const CollectGdalMessages&) = delete;
};

}  // namespace skyview::python
