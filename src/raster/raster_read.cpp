// Reading height rasters and result bands: one band read whole, unpacked and masked, with the
// checks every reader makes (the file opens as a raster, the band exists, values are usable).
#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_priv.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "raster/gdal_common.h"
#include "skyview/core/error.h"
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

Terrain read_terrain(const std::string& path, const ReadOptions& options, ReadReport* report) {
  RawBand raw = read_raw_band(path, options.band);
  const HeightUnit unit =
      height_unit(*raw.ds->GetRasterBand(options.band), raw.ds->GetSpatialRef(), options.z_scale, path);
  const int width = raw.width, height = raw.height;
  if (static_cast<std::int64_t>(width) * height < 2) {
    throw Error("'" + path + "' has a single cell: a horizon needs at least two cells");
  }
  std::vector<double>& values = raw.values;
  const int has_nodata = raw.has_nodata;
  const double nodata = raw.nodata;
  const bool nodata_is_nan = has_nodata && std::isnan(nodata);

  ReadReport rep;
  rep.has_nodata_value = has_nodata != 0;
  rep.nodata_value = nodata;
  rep.z_scale = unit.metres;
  rep.height_unit = unit.source;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t i = 0; i < values.size(); ++i) {
    double& v = values[i];
    if (raw.masked(i)) {
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
    v *= unit.metres;
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
  t.georef = georeference_of(*raw.ds);
  const auto& gt = t.georef.geotransform;
  if (t.georef.has_geotransform && (gt[1] * gt[5] - gt[2] * gt[4]) == 0.0) {
    throw Error("'" + path + "' has a degenerate geotransform (zero cell size)");
  }
  try {
    t.frame = GroundFrame(t.georef, width, height);
  } catch (const Error& e) {
    throw Error("'" + path + "': " + e.what());
  }
  t.full_width = width;
  t.full_height = height;
  if (report) *report = rep;
  return t;
}

}  // namespace skyview
