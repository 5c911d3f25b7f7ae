// Reading bands through GDAL, whole or by windows: what raster_read.cpp and terrain_reader.cpp
// share (raw_band.h).
#include "raster/raw_band.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"

namespace skyview::detail {

namespace {

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

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

DatasetPtr open_raster_band(const std::string& path, int band_index) {
  init_gdal();
  if (!path_exists(path)) throw Error("cannot open '" + path + "': no such file");
  CPLErrorReset();
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error("'" + path + "' is a folder, not a raster");
  DatasetPtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ds) {  // GDAL says nothing when no driver recognises the file
    throw Error("cannot open '" + path +
                "' as a raster: " + last_gdal_error("no GDAL driver reads it (corrupt, or not a raster format)"));
  }
  if (band_index < 1 || band_index > ds->GetRasterCount()) {
    throw Error("'" + path + "' has " + std::to_string(ds->GetRasterCount()) + " band(s); band " +
                std::to_string(band_index) + " does not exist");
  }
  return ds;
}

void read_raw_window(GDALDataset& ds, int band_index, const std::string& path, const Window& w, RawWindow& r) {
  const DecodeThreads decode_threads;
  GDALRasterBand* band = ds.GetRasterBand(band_index);
  r.width = w.cols, r.height = w.rows;
  r.values.resize(static_cast<std::size_t>(w.cols) * w.rows);
  if (band->RasterIO(GF_Read, w.col0, w.row0, w.cols, w.rows, r.values.data(), w.cols, w.rows, GDT_Float64, 0, 0) !=
      CE_None) {
    throw Error("cannot read band " + std::to_string(band_index) + " of '" + path +
                "': " + last_gdal_error("GDAL gives no reason; the file may be truncated or corrupt"));
  }
  r.nodata = band->GetNoDataValue(&r.has_nodata);
  // GDAL's mask says which cells hold data; a fill value under an alpha of 0 must not become a
  // height that occludes its neighbours.
  r.mask.clear();
  if ((band->GetMaskFlags() & (GMF_ALL_VALID | GMF_NODATA)) == 0) {
    r.mask.resize(r.values.size());
    if (band->GetMaskBand()->RasterIO(GF_Read, w.col0, w.row0, w.cols, w.rows, r.mask.data(), w.cols, w.rows, GDT_Byte,
                                      0, 0) != CE_None) {
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

void convert_heights(std::vector<double>& values, const std::vector<std::uint8_t>& mask, bool has_nodata, double nodata,
                     double metres, const ReadOptions& options, const std::string& path, const Window& w,
                     HeightScan& scan) {
  const bool nodata_is_nan = has_nodata && std::isnan(nodata);
  ReadReport& rep = scan.counts;
  rep.has_nodata_value = has_nodata;
  rep.nodata_value = nodata;
  rep.z_scale = metres;
  auto cell = [&](std::size_t i) {
    return "(" + std::to_string(w.col0 + static_cast<int>(i % w.cols)) + ", " +
           std::to_string(w.row0 + static_cast<int>(i / w.cols)) + ")";
  };
  for (std::size_t i = 0; i < values.size(); ++i) {
    double& v = values[i];
    if (!mask.empty() && mask[i] == 0) {
      v = std::numeric_limits<double>::quiet_NaN();
      ++rep.nodata_cells;
      ++rep.masked_cells;
      continue;
    }
    if (std::isnan(v)) {
      if (!nodata_is_nan) {
        if (!options.nan_is_nodata)
          throw Error("'" + path + "' holds NaN at cell " + cell(i) + " but its nodata value is not NaN");
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
    if (std::isinf(v))
      throw Error("'" + path + "' holds an infinite height at cell " + cell(i) + "; set it to the nodata value");
    v *= metres;
    scan.lo = std::min(scan.lo, v);
    scan.hi = std::max(scan.hi, v);
  }
}

void check_height_range(const std::string& path, const HeightScan& scan, std::int64_t cells, int band) {
  if (scan.counts.nodata_cells == cells)
    throw Error("'" + path + "' band " + std::to_string(band) + " holds only nodata");
  if (scan.hi - scan.lo > 1e5)
    throw Error("'" + path + "' spans more than 100 km of height; check --z-scale and nodata");
}

GroundFrame checked_frame(const std::string& path, const GeoReference& georef, int width, int height) {
  const auto& gt = georef.geotransform;
  if (georef.has_geotransform && (gt[1] * gt[5] - gt[2] * gt[4]) == 0.0) {
    throw Error("'" + path + "' has a degenerate geotransform (zero cell size)");
  }
  if (!georef.has_geotransform && !georef.crs_wkt.empty())
    throw Error("'" + path + "' has a CRS but no geotransform: where its cells lie is unknown");
  try {
    return GroundFrame(georef, width, height);
  } catch (const Error& e) {
    throw Error("'" + path + "': " + e.what());
  }
}

HeightUnit band_height_unit(GDALDataset& ds, const ReadOptions& options, const std::string& path,
                            GeoReference& georef) {
  OGRSpatialReference assigned;
  const OGRSpatialReference* crs = ds.GetSpatialRef();
  if (!options.assign_crs.empty()) {  // --s_srs: what the file's CRS is, as gdal_translate -a_srs states it
    georef.crs_wkt = crs_from_user_input(options.assign_crs, "--s_srs");
    assigned.importFromWkt(georef.crs_wkt.c_str());
    crs = &assigned;
  }
  return height_unit(*ds.GetRasterBand(options.band), crs, options.z_scale, path);
}

// Cells whose ground size and heights cannot both be metres give every angle wrong and no error:
// an ASCII grid in degrees without its .prj read as metres gave a mean svf of 0.12 where its CRS
// gives 0.72. Refused where the unit of either side was assumed; a raster without a CRS or a
// geotransform is said on stderr, since every distance rests on that assumption.
void check_units(const std::string& name, const GeoReference& g, int width, int height, const GroundFrame& frame,
                 double relief, const std::string& height_unit) {
  const bool no_crs = g.crs_wkt.empty();
  const bool heights_assumed = starts_with(height_unit, "metres (assumed");
  if (no_crs && g.has_geotransform) {
    const auto& gt = g.geotransform;
    const double x0 = g.x_of(-0.5, -0.5), y0 = g.y_of(-0.5, -0.5);
    const double x1 = g.x_of(width - 0.5, height - 0.5), y1 = g.y_of(width - 0.5, height - 0.5);
    const bool in_lon_lat =
        std::max(std::abs(x0), std::abs(x1)) <= 180.0 && std::max(std::abs(y0), std::abs(y1)) <= 90.0;
    const double cell = std::max(std::hypot(gt[1], gt[4]), std::hypot(gt[2], gt[5]));
    if (in_lon_lat && cell < 0.01) {
      throw Error("'" + name + "' has no CRS, and its cells (" + number_text(cell) +
                  " units) and extent look like degrees of longitude and latitude, not metres; give --s_srs with "
                  "its CRS (EPSG:4326 for WGS 84 degrees)");
    }
  }
  const double cell = frame.at(0.5 * width, 0.5 * height).min_cell_size();
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

}  // namespace skyview::detail
