#include "skyview/raster/georeference.h"

namespace skyview {

GeoReference GeoReference::window(int col0, int row0) const {
  GeoReference out = *this;
  const auto& g = geotransform;
  out.geotransform[0] = g[0] + col0 * g[1] + row0 * g[2];
  out.geotransform[3] = g[3] + col0 * g[4] + row0 * g[5];
  return out;
}

}  // namespace skyview
