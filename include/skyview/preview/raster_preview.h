#pragma once
// PNG previews of result bands, one module for every command: a colour ramp suited to the
// quantity, a legend with the ramp's values and unit, a title, and (for georeferenced rasters) a
// scale bar, a north arrow and a world file so the picture lays over a map in QGIS. Nodata (NaN)
// is transparent. docs/previews.md shows them.
#include <optional>
#include <string>
#include <utility>

#include "skyview/core/grid.h"
#include "skyview/preview/colour_ramp.h"
#include "skyview/raster/georeference.h"

namespace skyview {

struct PreviewSpec {
  std::string title;  // "svf - city_svf.tif"
  std::string band;   // the band drawn ("svf")
  std::string unit;   // "1", "degree", "kWh m-2"
  ColourRamp ramp = ColourRamp::viridis;
  // Fixed ramp limits (--preview-range MIN,MAX) so two previews compare; unset: stretched to the
  // data (preview_range).
  std::optional<std::pair<double, double>> range;
  // Of the raster drawn; without a geotransform no scale bar, north arrow or world file.
  GeoReference georef;
};

// The stretch's percentiles of the valid values: the ramp runs from the 2nd to the 98th, so that
// a few extreme cells (a mast, a pit) do not flatten the rest into one colour.
constexpr double kStretchLowPercentile = 2.0, kStretchHighPercentile = 98.0;

// Writes `values` (NaN = nodata) as an RGBA PNG at `path`, atomically, with the legend, title,
// scale bar and north arrow; PATH.aux.xml holds what it draws (PREVIEW_BAND, _UNIT, _RAMP,
// _RANGE, _TITLE) and, for a georeferenced raster, its CRS beside PATH's world file (".pgw"). Throws skyview::Error if
// any of them exists and !overwrite, or if writing fails.
void write_raster_preview(const std::string& path, const Grid<float>& values, const PreviewSpec& spec, bool overwrite);

// The ramp's limits for `values` under `spec`: its range if set, else the stretch: the 2nd and
// 98th percentiles of the valid values (symmetric about zero for the diverging ramp: minus and
// plus the 98th percentile of the absolute values), widened where they coincide. {0, 1} where no
// value is valid.
std::pair<double, double> preview_range(const Grid<float>& values, const PreviewSpec& spec);

// The world file beside a PNG: "out.png" -> "out.pgw".
std::string world_file_path(const std::string& png_path);

}  // namespace skyview
