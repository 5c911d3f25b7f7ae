#include "arrays.h"

#include <cpl_error.h>
#include <ogr_spatialref.h>

#include <cmath>

#include "skyview/core/error.h"
#include "skyview/raster/ground_frame.h"
#include "skyview/raster/height_unit.h"
#include "skyview/raster/raster_read.h"

namespace skyview::python {

namespace {

// The name messages give the height array (read_terrain names the file).
constexpr const char* kName = "z";

void CPL_STDCALL collect(CPLErr level, CPLErrorNum, const char* message) {
  auto* lines = static_cast<std::vector<std::string>*>(CPLGetErrorHandlerUserData());
  if (lines && level >= CE_Warning) lines->push_back(message);
}

bool finite_positive(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

CollectGdalMessages::CollectGdalMessages(std::vector<std::string>& lines) { CPLPushErrorHandlerEx(collect, &lines); }
CollectGdalMessages::~CollectGdalMessages() { CPLPopErrorHandler(); }

Terrain terrain_from_array(const py::handle& z, const ArrayGeoreference& where, std::vector<std::string>& warnings) {
  if (!py::isinstance<py::array>(z)) throw UsageError("z must be a 2-D NumPy array of heights");
  const auto array = py::reinterpret_borrow<py::array>(z);
  if (array.ndim() != 2) {
    throw UsageError("z must be a 2-D array of heights (rows, cols), not " + std::to_string(array.ndim()) + "-D");
  }
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw UsageError("z must hold real numbers (float or integer), not dtype " + std::string(py::str(array.dtype())));
  }
  const py::ssize_t rows = array.shape(0), cols = array.shape(1);
  if (rows < 1 || cols < 1) {
    throw UsageError("z is empty (" + std::to_string(rows) + " x " + std::to_string(cols) + ")");
  }
  if (rows > (1 << 30) / 4 || cols > (1 << 30) / 4) throw UsageError("z has too many rows or columns");

  HeightValues h;
  h.name = kName;
  h.width = static_cast<int>(cols);
  h.height = static_cast<int>(rows);
  // One copy whatever the layout and dtype: heights go to double here and to float relative to a
  // base height in the Terrain, so a float32 array cannot be shared.
  const auto heights = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  h.values.assign(heights.data(), heights.data() + heights.size());
  if (where.height_range) h.raster_height_range = std::make_pair((*where.height_range)[0], (*where.height_range)[1]);
  if (where.nodata) {
    h.has_nodata = true;
    h.nodata = *where.nodata;
  }

  GeoReference& g = h.georef;
  if (where.cell_size && where.transform) {
    throw UsageError("give cell_size or transform, not both (a transform holds the cell size)");
  }
  if (where.transform) {
    const std::vector<double>& t = *where.transform;
    if (t.size() != 6) {
      throw UsageError(
          "transform must be 6 numbers in GDAL's order (x0, cell width, row rotation, y0, column "
          "rotation, cell height; rasterio: transform.to_gdal()), not " +
          std::to_string(t.size()));
    }
    for (int i = 0; i < 6; ++i) {
      if (!std::isfinite(t[static_cast<std::size_t>(i)])) throw UsageError("transform holds a non-finite number");
      g.geotransform[static_cast<std::size_t>(i)] = t[static_cast<std::size_t>(i)];
    }
    g.has_geotransform = true;
  } else if (where.cell_size) {
    if (!finite_positive(*where.cell_size)) {
      throw UsageError("cell_size must be a positive finite number of metres, not " +
                       std::string(py::str(py::float_(*where.cell_size))));
    }
    g.geotransform = {0.0, *where.cell_size, 0.0, 0.0, 0.0, -*where.cell_size};
    g.has_geotransform = true;
  } else {
    throw UsageError("give cell_size (metres) or transform (with crs) to say how large the cells are");
  }
  if (where.crs) g.crs_wkt = crs_from_user_input(*where.crs, "crs");

  if (where.z_scale) {
    if (!finite_positive(*where.z_scale)) throw UsageError("z_scale must be a positive finite number");
    h.metres = *where.z_scale;
    h.height_unit = "z_scale";
  } else {
    OGRSpatialReference srs;
    if (!g.crs_wkt.empty()) srs.importFromWkt(g.crs_wkt.c_str());
    const HeightUnit unit = unstated_height_unit(g.crs_wkt.empty() ? nullptr : &srs, kName, "z_scale");
    h.metres = unit.metres;
    h.height_unit = unit.source;
  }

  std::vector<std::string> gdal_lines;
  ReadReport report;
  Terrain terrain;
  {
    CollectGdalMessages collect_messages(gdal_lines);
    terrain = terrain_from_heights(std::move(h), ReadOptions{}, &report);
  }
  if (where.tile) {
    const auto [col0, row0, full_width, full_height] = *where.tile;
    if (col0 < 0 || row0 < 0 || col0 + terrain.width() > full_width || row0 + terrain.height() > full_height)
      throw UsageError("the tile does not lie within the raster (internal error)");
    const GeoReference whole = terrain.georef;
    terrain.frame = GroundFrame(whole, full_width, full_height);
    terrain.georef = whole.window(col0, row0);
    terrain.origin_col = col0;
    terrain.origin_row = row0;
    terrain.full_width = full_width;
    terrain.full_height = full_height;
  }
  for (const std::string& line : gdal_lines) {
    // A cell size in metres says what a missing CRS would: the coordinates are metres on a plane.
    if (where.cell_size && !where.crs && line.find("has no CRS") != std::string::npos) continue;
    warnings.push_back(line);
  }
  if (report.undeclared_nan_cells > 0 && where.nodata && !std::isnan(*where.nodata)) {
    warnings.push_back(std::to_string(report.undeclared_nan_cells) +
                       " NaN cells in z are not the declared nodata value; treated as nodata");
  }
  return terrain;
}

py::array_t<float> to_numpy(std::vector<float>&& values, const std::vector<py::ssize_t>& shape) {
  auto* owned = new std::vector<float>(std::move(values));
  py::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<float>*>(p); });
  return py::array_t<float>(shape, owned->data(), free_when_done);
}

void warn_all(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) {
    if (PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 2) < 0) throw py::error_already_set();  // warnings as errors
  }
}

}  // namespace skyview::python
