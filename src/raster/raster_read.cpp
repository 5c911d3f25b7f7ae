// Reading height rasters and result bands: one band read whole, unpacked and masked, with the
// checks every reader makes (the file opens as a raster, the band exists, values are usable).
#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "raster/gdal_common.h"
#include "raster/raw_band.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/raster/height_unit.h"
#include "skyview/raster/raster_read.h"

namespace skyview {

using namespace detail;

BandPacking band_packing(GDALRasterBand& band, const std::string& path, int band_index) {
  BandPacking p;
  p.scale = band.GetScale();  // 1 and 0 where the band states none
  p.offset = band.GetOffset();
  if (!std::isfinite(p.scale) || p.scale == 0.0 || !std::isfinite(p.offset)) {
    throw Error("band " + std::to_string(band_index) + " of '" + path + "' has an unusable scale or offset");
  }
  return p;
}

namespace {

// The cells of `window` of an open band.
RasterBand band_window(GDALDataset& ds, int band_index, const std::string& path, const Window& window) {
  RawWindow raw;
  read_raw_window(ds, band_index, path, window, raw);
  RasterBand out;
  out.values = Grid<float>(raw.width, raw.height);
  for (std::size_t i = 0; i < raw.values.size(); ++i) {
    const double v = raw.values[i];
    out.values.values()[i] = raw.masked(i) || (raw.has_nodata && v == raw.nodata)
                                 ? std::numeric_limits<float>::quiet_NaN()
                                 : static_cast<float>(v);
  }
  // The whole raster's georeference as stored; a window's moved to its first cell.
  const GeoReference georef = georeference_of(ds);
  out.georef = window.col0 == 0 && window.row0 == 0 ? georef : georef.window(window.col0, window.row0);
  const char* description = ds.GetRasterBand(band_index)->GetDescription();
  out.description = description ? description : "";
  const char* unit = ds.GetRasterBand(band_index)->GetUnitType();
  out.unit = unit ? unit : "";
  return out;
}

}  // namespace

RasterBand read_band(const std::string& path, int band_index) {
  DatasetPtr ds = open_raster_band(path, band_index);
  return band_window(*ds, band_index, path, {0, 0, ds->GetRasterXSize(), ds->GetRasterYSize()});
}

RasterBand read_band(const std::string& path, int band_index, const Window& window) {
  DatasetPtr ds = open_raster_band(path, band_index);
  if (window.col0 < 0 || window.row0 < 0 || window.cols < 1 || window.rows < 1 ||
      window.col0 + window.cols > ds->GetRasterXSize() || window.row0 + window.rows > ds->GetRasterYSize())
    throw Error("'" + path + "' has no cells " + std::to_string(window.col0) + ".." +
                std::to_string(window.col0 + window.cols - 1) + ", " + std::to_string(window.row0) + ".." +
                std::to_string(window.row0 + window.rows - 1));
  return band_window(*ds, band_index, path, window);
}

Terrain terrain_from_heights(HeightValues&& h, const ReadOptions& options, ReadReport* report) {
  const std::string& path = h.name;
  const int width = h.width, height = h.height;
  if (width < 1 || height < 1 || h.values.size() != static_cast<std::size_t>(width) * height)
    throw Error("'" + path + "' holds no grid of heights (internal error)");
  if (static_cast<std::int64_t>(width) * height < 2) {
    throw Error("'" + path + "' has a single cell: a horizon needs at least two cells");
  }
  std::vector<double>& values = h.values;
  HeightScan scan;
  convert_heights(values, h.mask, h.has_nodata, h.nodata, h.metres, options, path, {0, 0, width, height}, scan);
  check_height_range(path, scan, static_cast<std::int64_t>(values.size()), options.band);
  ReadReport& rep = scan.counts;
  rep.height_unit = h.height_unit;

  Terrain t;
  t.base_height = h.raster_height_range
                      ? 0.5 * (h.raster_height_range->first * h.metres + h.raster_height_range->second * h.metres)
                      : 0.5 * (scan.lo + scan.hi);
  t.heights = Grid<float>(width, height);
  for (std::size_t i = 0; i < values.size(); ++i) t.heights.values()[i] = static_cast<float>(values[i] - t.base_height);
  t.georef = std::move(h.georef);
  t.frame = checked_frame(path, t.georef, width, height);
  t.full_width = width;
  t.full_height = height;
  check_units(path, t.georef, width, height, t.frame, scan.hi - scan.lo, h.height_unit);
  if (report) *report = rep;
  return t;
}

std::string crs_from_user_input(const std::string& text, const std::string& option) {
  init_gdal();
  OGRSpatialReference srs;
  const CPLErrorHandlerPusher quiet(CPLQuietErrorHandler);
  if (srs.SetFromUserInput(text.c_str()) != OGRERR_NONE)
    throw UsageError(option + " '" + text + "' is not a CRS GDAL knows (EPSG:25833, a WKT or PROJ string)");
  char* wkt = nullptr;
  const char* opts[] = {"FORMAT=WKT2_2018", nullptr};
  srs.exportToWkt(&wkt, opts);
  std::string out = wkt ? wkt : "";
  CPLFree(wkt);
  return out;
}

Terrain read_terrain(const std::string& path, const ReadOptions& options, ReadReport* report) {
  DatasetPtr ds = open_raster_band(path, options.band);
  RawWindow raw;
  read_raw_window(*ds, options.band, path, {0, 0, ds->GetRasterXSize(), ds->GetRasterYSize()}, raw);
  HeightValues h;
  h.name = path;
  h.width = raw.width;
  h.height = raw.height;
  h.georef = georeference_of(*ds);
  const HeightUnit unit = band_height_unit(*ds, options, path, h.georef);
  h.metres = unit.metres;
  h.height_unit = unit.source;
  h.values = std::move(raw.values);
  h.mask = std::move(raw.mask);
  h.has_nodata = raw.has_nodata != 0;
  h.nodata = raw.nodata;
  return terrain_from_heights(std::move(h), options, report);
}

}  // namespace skyview
