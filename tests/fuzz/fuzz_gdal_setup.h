#pragma once
// The readers' one call into the raster module, for fuzz targets that link a reader alone: register
// GDAL's drivers, with GDAL's own messages silenced (the fuzzer feeds it garbage by design).
#include <cpl_error.h>
#include <gdal.h>

namespace skyview {
inline void init_gdal_for_fuzzing() {
  static const bool once = [] {
    GDALAllRegister();
    CPLSetErrorHandler(CPLQuietErrorHandler);
    return true;
  }();
  (void)once;
}
void init_gdal() { init_gdal_for_fuzzing(); }
}  // namespace skyview
