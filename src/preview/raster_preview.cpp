#include "skyview/preview/raster_preview.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "skyview/raster/raster_io.h"

namespace skyview {

// A first version: the range only, drawn grey. The colour ramps, legend, scale bar, north arrow
// and world file follow (issue 32).
std::pair<double, double> preview_range(const Grid<float>& values, const PreviewSpec& spec) {
  if (spec.range) return *spec.range;
  double lo = INFINITY, hi = -INFINITY;
  for (float v : values.values()) {
    if (std::isnan(v)) continue;
    lo = std::min(lo, static_cast<double>(v));
    hi = std::max(hi, static_cast<double>(v));
  }
  if (!(lo <= hi)) return {0.0, 1.0};
  return {lo, hi};
}

void write_raster_preview(const std::string& path, const Grid<float>& values, const PreviewSpec& spec,
                          bool overwrite) {
  const auto [lo, hi] = preview_range(values, spec);
  write_preview_png(path, values.width(), values.height(), values.data(), lo, hi, overwrite);
}

}  // namespace skyview
