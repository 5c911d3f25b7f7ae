#pragma once
// PNG previews of result bands, one module for every command: a colour ramp suited to the
// quantity, a legend with the ramp's values and unit, a title, and (for georeferenced rasters) a
// scale bar, a north arrow and a world file so the picture lays over a map in QGIS. Nodata (NaN)
// is transparent.
#include <optional>
#include <string>
#include <utility>

#include "skyview/core/grid.h"
#include "skyview/raster/georeference.h"

namespace skyview {

// Perceptually uniform ramps: sequential for quantities (viridis, cividis, magma), diverging for
// differences (a blue-white-red centred on zero), grey for masks.
enum class ColourRamp { viridis, cividis, magma, diverging, grey };

struct PreviewSpec {
  std::string title;  // "svf - city_svf.tif"
  std::string band;   // the band drawn ("svf")
  std::string unit;   // "1", "degree", "kWh m-2"
  ColourRamp ramp = ColourRamp::viridis;
  // Fixed ramp limits (--preview-range MIN,MAX) so two previews compare; unset: stretched to the
  // data (docs/previews.md says how).
  std::optional<std::pair<double, double>> range;
  // Of the raster drawn; without a geotransform no scale bar, north arrow or world file.
  GeoReference georef;
};

// Writes `values` (NaN = nodata) as a PNG at `path`, atomically. Throws skyview::Error if `path`
// exists and !overwrite, or if writing fails.
void write_raster_preview(const std::string& path, const Grid<float>& values, const PreviewSpec& spec,
                          bool overwrite);

// The ramp's limits for `values` under `spec` (its range, or the stretch).
std::pair<double, double> preview_range(const Grid<float>& values, const PreviewSpec& spec);

}  // namespace skyview
