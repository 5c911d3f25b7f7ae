#pragma once
// Where a raster sits on the Earth: GDAL's affine geotransform and the CRS as WKT.
#include <array>
#include <string>

namespace skyview {

struct GeoReference {
  // GDAL order: x0, pixel width, row rotation, y0, column rotation, pixel height (negative for north-up).
  std::array<double, 6> geotransform{0, 1, 0, 0, 0, -1};
  bool has_geotransform = false;
  std::string crs_wkt;  // empty when the raster carries no CRS

  // Centre of a cell in CRS coordinates.
  double x_of(double col, double row) const {
    return geotransform[0] + (col + 0.5) * geotransform[1] + (row + 0.5) * geotransform[2];
  }
  double y_of(double col, double row) const {
    return geotransform[3] + (col + 0.5) * geotransform[4] + (row + 0.5) * geotransform[5];
  }
  // The same georeference for a sub-window whose top-left cell is (col0, row0).
  GeoReference window(int col0, int row0) const;
};

}  // namespace skyview
