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
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/raster/height_unit.h"
#include "skyview/raster/raster_read.h"

namespace skyview {

using namespace detail;

namespace {

// One band of a raster read whole as doubles, with what every reader checks: the file opens as a
// raster, the band exists.
struct RawBand {
  DatasetPtr ds;
  int width = 0, height = 0;
  std::vector<double> values;
  int has_nodata = 0;
  double nodata = 0;
  // The band's mask where it is not just the nodata value (an alpha band, a .msk file, a GeoTIFF's
  // internal mask): 0 marks a cell without data, whatever its value. Empty when every cell is valid
  // or the nodata value alone says which are not.
  std::vector<std::uint8_t> mask;
  bool masked(std::size_t i) const { return !mask.empty() && mask[i] == 0; }
};

// Decodes a compressed raster's blocks on the run's threads, unless the user set GDAL_NUM_THREADS:
// one thread took 0.36-0.43 s to read a 4000 x 4000 DEFLATE GeoTIFF, two 0.12-0.14 s. Thread-local,
// so that nothing else this thread does later sees it.
class DecodeThreads {
 public:
  DecodeThreads() {
    if (CPLGetConfigOption("GDAL_NUM_THREADS", nullptr)) return;
    CPLSetThreadLocalConfigOption("GDAL_NUM_THREADS", run_threads_text().c_str());
    set_ = true;
  }
  ~DecodeThreads() {
    if (set_) CPLSetThreadLocalConfigOption("GDAL_NUM_THREADS", nullptr);
  }
  DecodeThreads(const DecodeThreads&) = delete;
  DecodeThreads& operator=(const DecodeThreads&) = delete;

 private:
  bool set_ = false;
};

RawBand read_raw_band(const std::string& path, int band_index) {
  init_gdal();
  if (!path_exists(path)) throw Error("cannot open '" + path + "': no such file");
  CPLErrorReset();
  RawBand r;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error("'" + path + "' is a folder, not a raster");
  const DecodeThreads decode_threads;
  r.ds.reset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!r.ds) {  // GDAL says nothing when no driver recognises the file
    throw Error("cannot open '" + path +
                "' as a raster: " + last_gdal_error("no GDAL driver reads it (corrupt, or not a raster format)"));
  }
  r.width = r.ds->GetRasterXSize(), r.height = r.ds->GetRasterYSize();
  if (band_index < 1 || band_index > r.ds->GetRasterCount()) {
    throw Error("'" + path + "' has " + std::to_string(r.ds->GetRasterCount()) + " band(s); band " +
                std::to_string(band_index) + " does not exist");
  }
  GDALRasterBand* band = r.ds->GetRasterBand(band_index);
  r.values.resize(static_cast<std::size_t>(r.width) * r.height);
  if (band->RasterIO(GF_Read, 0, 0, r.width, r.height, r.values.data(), r.width, r.height, GDT_Float64, 0, 0) !=
      CE_None) {
    throw Error("cannot read band " + std::to_string(band_index) + " of '" + path +
                "': " + last_gdal_error("GDAL gives no reason; the file may be truncated or corrupt"));
  }
  r.nodata = band->GetNoDataValue(&r.has_nodata);
  // GDAL's mask says which cells hold data; a fill value under an alpha of 0 must not become a
  // height that occludes its neighbours.
  if ((band->GetMaskFlags() & (GMF_ALL_VALID | GMF_NODATA)) == 0) {
    r.mask.resize(r.values.size());
    if (band->GetMaskBand()->RasterIO(GF_Read, 0, 0, r.width, r.height, r.mask.data(), r.width, r.height, GDT_Byte, 0,
                                      0) != CE_None) {
      throw Error("cannot read the mask of band " + std::to_string(band_index) + " of '" + path +
                  "': " + last_gdal_error("GDAL gives no reason; the file may be truncated or corrupt"));
    }
  }
  // Unpacked nodata first (it is a raw value), so that a scaled value can never pass for nodata.
  if (const BandPacking packing = band_packing(*band, path, band_index); packing.packed()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (double& v : r.values) v = r.has_nodata && v == r.nodata ? nan : v * packing.scale + packing.offset;
    if (r.has_nodata) r.nodata = nan;
  }
  return r;
}

GeoReference georeference_of(GDALDataset& ds) {
  GeoReference g;
  double gt[6];
  g.has_geotransform = ds.GetGeoTransform(gt) == CE_None;
  // Without one GDAL gives (0, 1, 0, 0, 0, 1), whose rows run north; an image's first row is its
  // top, as QGIS shows it, so the default stays north-up.
  if (g.has_geotransform) std::copy(gt, gt + 6, g.geotransform.begin());
  if (const OGRSpatialReference* srs = ds.GetSpatialRef()) {
    char* wkt = nullptr;
    const char* opts[] = {"FORMAT=WKT2_2018", nullptr};
    srs->exportToWkt(&wkt, opts);
    g.crs_wkt = wkt ? wkt : "";
    CPLFree(wkt);
  }
  return g;
}

}  // namespace

BandPacking band_packing(GDALRasterBand& band, const std::string& path, int band_index) {
  BandPacking p;
  p.scale = band.GetScale();  // 1 and 0 where the band states none
  p.offset = band.GetOffset();
  if (!std::isfinite(p.scale) || p.scale == 0.0 || !std::isfinite(p.offset)) {
    throw Error("band " + std::to_string(band_index) + " of '" + path + "' has an unusable scale or offset");
  }
  return p;
}

RasterBand read_band(const std::string& path, int band_index) {
  RawBand raw = read_raw_band(path, band_index);
  RasterBand out;
  out.values = Grid<float>(raw.width, raw.height);
  for (std::size_t i = 0; i < raw.values.size(); ++i) {
    const double v = raw.values[i];
    out.values.values()[i] = raw.masked(i) || (raw.has_nodata && v == raw.nodata)
                                 ? std::numeric_limits<float>::quiet_NaN()
                                 : static_cast<float>(v);
  }
  out.georef = georeference_of(*raw.ds);
  const char* description = raw.ds->GetRasterBand(band_index)->GetDescription();
  out.description = description ? description : "";
  const char* unit = raw.ds->GetRasterBand(band_index)->GetUnitType();
  out.unit = unit ? unit : "";
  return out;
}

namespace {

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// Cells whose ground size and heights cannot both be metres give every angle wrong and no error:
// an ASCII grid in degrees without its .prj read as metres gave a mean svf of 0.12 where its CRS
// gives 0.72. Refused where the unit of either side was assumed; a raster without a CRS or a
// geotransform is said on stderr, since every distance rests on that assumption.
void check_units(const std::string& name, const Terrain& t, double relief, const std::string& height_unit) {
  const GeoReference& g = t.georef;
  const bool no_crs = g.crs_wkt.empty();
  const bool heights_assumed = starts_with(height_unit, "metres (assumed");
  if (no_crs && g.has_geotransform) {
    const auto& gt = g.geotransform;
    const double x0 = g.x_of(-0.5, -0.5), y0 = g.y_of(-0.5, -0.5);
    const double x1 = g.x_of(t.width() - 0.5, t.height() - 0.5), y1 = g.y_of(t.width() - 0.5, t.height() - 0.5);
    const bool in_lon_lat =
        std::max(std::abs(x0), std::abs(x1)) <= 180.0 && std::max(std::abs(y0), std::abs(y1)) <= 90.0;
    const double cell = std::max(std::hypot(gt[1], gt[4]), std::hypot(gt[2], gt[5]));
    if (in_lon_lat && cell < 0.01) {
      throw Error("'" + name + "' has no CRS, and its cells (" + number_text(cell) +
                  " units) and extent look like degrees of longitude and latitude, not metres; give --s_srs with "
                  "its CRS (EPSG:4326 for WGS 84 degrees)");
    }
  }
  const double cell = raster_centre_jacobian(t).min_cell_size();
  if ((no_crs || heights_assumed) && cell < 0.05 && relief > 10.0) {
    throw Error("'" + name + "' has cells of " + number_text(cell) + " m against " + number_text(relief) +
                " m of relief: its cells and heights cannot both be metres; give --s_srs with its CRS, or --z-scale "
                "with its heights' unit");
  }
  if (!g.has_geotransform) {
    CPLError(CE_Warning, CPLE_AppDefined,
             "'%s' has no geotransform: its cells are taken as 1 m squares, north up (give it a geotransform, e.g. "
             "gdal_translate -a_ullr, and a CRS)",
             name.c_str());
  } else if (no_crs) {
    CPLError(CE_Warning, CPLE_AppDefined,
             "'%s' has no CRS: its coordinates are taken as metres on a flat plane (give --s_srs to state its CRS)",
             name.c_str());
  }
}

}  // namespace

Terrain terrain_from_heights(HeightValues&& h, const ReadOptions& options, ReadReport* report) {
  const std::string& path = h.name;
  const int width = h.width, height = h.height;
  if (width < 1 || height < 1 || h.values.size() != static_cast<std::size_t>(width) * height)
    throw Error("'" + path + "' holds no grid of heights (internal error)");
  if (static_cast<std::int64_t>(width) * height < 2) {
    throw Error("'" + path + "' has a single cell: a horizon needs at least two cells");
  }
  std::vector<double>& values = h.values;
  const bool has_nodata = h.has_nodata;
  const double nodata = h.nodata;
  const bool nodata_is_nan = has_nodata && std::isnan(nodata);
  auto masked = [&](std::size_t i) { return !h.mask.empty() && h.mask[i] == 0; };

  ReadReport rep;
  rep.has_nodata_value = has_nodata;
  rep.nodata_value = nodata;
  rep.z_scale = h.metres;
  rep.height_unit = h.height_unit;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t i = 0; i < values.size(); ++i) {
    double& v = values[i];
    if (masked(i)) {
      v = std::numeric_limits<double>::quiet_NaN();
      ++rep.nodata_cells;
      ++rep.masked_cells;
      continue;
    }
    if (std::isnan(v)) {
      if (!nodata_is_nan) {
        if (!options.nan_is_nodata) {
          throw Error("'" + path + "' holds NaN at cell (" + std::to_string(i % width) + ", " +
                      std::to_string(i / width) + ") but its nodata value is not NaN");
        }
        ++rep.undeclared_nan_cells;
      }
      ++rep.nodata_cells;
      continue;
    }
    if (has_nodata && v == nodata) {
      v = std::numeric_limits<double>::quiet_NaN();
      ++rep.nodata_cells;
      continue;
    }
    if (std::isinf(v)) {
      throw Error("'" + path + "' holds an infinite height at cell (" + std::to_string(i % width) + ", " +
                  std::to_string(i / width) + "); set it to the nodata value");
    }
    v *= h.metres;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (rep.nodata_cells == static_cast<std::int64_t>(values.size())) {
    throw Error("'" + path + "' band " + std::to_string(options.band) + " holds only nodata");
  }
  if (hi - lo > 1e5) throw Error("'" + path + "' spans more than 100 km of height; check --z-scale and nodata");

  Terrain t;
  t.base_height = 0.5 * (lo + hi);
  t.heights = Grid<float>(width, height);
  for (std::size_t i = 0; i < values.size(); ++i) t.heights.values()[i] = static_cast<float>(values[i] - t.base_height);
  t.georef = std::move(h.georef);
  const auto& gt = t.georef.geotransform;
  if (t.georef.has_geotransform && (gt[1] * gt[5] - gt[2] * gt[4]) == 0.0) {
    throw Error("'" + path + "' has a degenerate geotransform (zero cell size)");
  }
  if (!t.georef.has_geotransform && !t.georef.crs_wkt.empty())
    throw Error("'" + path + "' has a CRS but no geotransform: where its cells lie is unknown");
  try {
    t.frame = GroundFrame(t.georef, width, height);
  } catch (const Error& e) {
    throw Error("'" + path + "': " + e.what());
  }
  t.full_width = width;
  t.full_height = height;
  check_units(path, t, hi - lo, h.height_unit);
  if (report) *report = rep;
  return t;
}

std::string crs_from_user_input(const std::string& text, const std::string& option) {
  init_gdal();
  OGRSpatialReference srs;
  const CPLErrorHandlerPusher quiet(CPLQuietErrorHandler);
  if (srs.SetFromUserInput(text.c_str()) != OGRERR_NONE)
    throw Error(option + " '" + text + "' is not a CRS GDAL knows (EPSG:25833, a WKT or PROJ string)");
  char* wkt = nullptr;
  const char* opts[] = {"FORMAT=WKT2_2018", nullptr};
  srs.exportToWkt(&wkt, opts);
  std::string out = wkt ? wkt : "";
  CPLFree(wkt);
  return out;
}

Terrain read_terrain(const std::string& path, const ReadOptions& options, ReadReport* report) {
  RawBand raw = read_raw_band(path, options.band);
  HeightValues h;
  h.name = path;
  h.width = raw.width;
  h.height = raw.height;
  h.georef = georeference_of(*raw.ds);
  OGRSpatialReference assigned;
  const OGRSpatialReference* crs = raw.ds->GetSpatialRef();
  if (!options.assign_crs.empty()) {  // --s_srs: what the file's CRS is, as gdal_translate -a_srs states it
    h.georef.crs_wkt = crs_from_user_input(options.assign_crs, "--s_srs");
    assigned.importFromWkt(h.georef.crs_wkt.c_str());
    crs = &assigned;
  }
  const HeightUnit unit = height_unit(*raw.ds->GetRasterBand(options.band), crs, options.z_scale, path);
  h.metres = unit.metres;
  h.height_unit = unit.source;
  h.values = std::move(raw.values);
  h.mask = std::move(raw.mask);
  h.has_nodata = raw.has_nodata != 0;
  h.nodata = raw.nodata;
  return terrain_from_heights(std::move(h), options, report);
}

}  // namespace skyview
