#include "skyview/raster/raster_io.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <cpl_vsi.h>
#include <gdal_priv.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <optional>
#include <sstream>

#include "raster/netcdf_names.h"
#include "skyview/core/error.h"
#include "skyview/raster/height_unit.h"
#include "skyview/core/lowercase.h"
#include "skyview/raster/temporary_outputs.h"

namespace skyview {

namespace {

void CPL_STDCALL quiet_error_handler(CPLErr level, CPLErrorNum, const char* msg) {
  // Failures become skyview::Error with our own wording; only warnings go straight to stderr.
  if (level == CE_Warning) std::fprintf(stderr, "Warning: %s\n", msg);
}

struct DatasetCloser {
  void operator()(GDALDataset* ds) const { GDALClose(ds); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

bool path_exists(const std::string& path) {
  VSIStatBufL st;
  return VSIStatL(path.c_str(), &st) == 0;
}

// GDAL's last message, or `otherwise` where it said nothing.
std::string last_gdal_error(const char* otherwise = "unknown GDAL error") {
  const char* m = CPLGetLastErrorMsg();
  return m && *m ? std::string(m) : std::string(otherwise);
}

}  // namespace

void init_gdal() {
  static std::once_flag once;
  std::call_once(once, [] {
    GDALAllRegister();
    CPLSetErrorHandler(quiet_error_handler);
    // Rasters are read whole and written a band at a time, so GDAL's block cache only holds
    // written tiles until they are flushed; its default (5% of the machine's memory) made it
    // most of `skyview horizon`'s peak (1.3 GB of 1.31 at 2000 x 2000, 64 directions, on 23 GB).
    // At most 64 MB unless the user sets GDAL_CACHEMAX; no slower.
    constexpr std::int64_t kCache = std::int64_t{64} << 20;
    if (!CPLGetConfigOption("GDAL_CACHEMAX", nullptr) && GDALGetCacheMax64() > kCache) GDALSetCacheMax64(kCache);
  });
}

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

// The threads the run may use (--threads), as GDAL's options want them: GDAL decodes and compresses
// blocks on its own threads, outside oneTBB's pool.
std::string run_threads_text() {
  return std::to_string(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

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

void check_output_writable(const std::string& path, bool overwrite) {
  if (path.empty()) throw Error("no output file given");
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec)) {
    throw Error("output '" + path + "' exists and is not a regular file; give another path");
  }
  if (path_exists(path) && !overwrite) throw Error("output '" + path + "' exists; use --overwrite to replace it");
  const auto dir = std::filesystem::path(path).parent_path();
  if (!dir.empty() && !std::filesystem::is_directory(dir)) {
    throw Error("cannot write '" + path + "': folder '" + dir.string() + "' does not exist");
  }
}

namespace {

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (std::filesystem::exists(a, ec) && std::filesystem::exists(b, ec)) return std::filesystem::equivalent(a, b, ec);
  const auto ca = std::filesystem::weakly_canonical(a, ec);
  if (ec) return a == b;
  const auto cb = std::filesystem::weakly_canonical(b, ec);
  return ec ? a == b : ca == cb;
}

}  // namespace

void check_outputs_apart(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs) {
  // The files an input reads: a VRT (or a format with side files) reads more than its own path.
  init_gdal();
  std::vector<std::string> read;
  for (const std::string& in : inputs) {
    if (in.empty()) continue;
    read.push_back(in);
    CPLErrorReset();
    const CPLErrorHandlerPusher quiet(CPLQuietErrorHandler);
    GDALDatasetUniquePtr ds(GDALDataset::Open(in.c_str(), GDAL_OF_RASTER | GDAL_OF_VECTOR | GDAL_OF_READONLY));
    if (!ds) continue;
    char** files = ds->GetFileList();
    for (char** f = files; f && *f; ++f) read.emplace_back(*f);
    CSLDestroy(files);
  }
  CPLErrorReset();  // a failed open here is no error of the run's
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    if (outputs[i].empty()) continue;
    for (const std::string& in : read) {
      if (!in.empty() && same_file(outputs[i], in)) {
        throw Error("output '" + outputs[i] + "' is also an input ('" + in + "'); give another output path");
      }
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (!outputs[j].empty() && same_file(outputs[i], outputs[j])) {
        throw Error(outputs[j] == outputs[i]
                        ? "two outputs are both '" + outputs[i] + "'; give each its own file"
                        : "'" + outputs[j] + "' and '" + outputs[i] + "' name the same output file");
      }
    }
  }
}

void write_output_file(const std::string& path, const std::string& bytes, bool overwrite) {
  check_output_writable(path, overwrite);
  const std::string tmp = temporary_output_name(path);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << bytes;
    out.close();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      forget_temporary(tmp);
      throw Error("cannot write '" + path + "'");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  forget_temporary(tmp);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw Error("cannot move the finished output into place at '" + path + "'");
  }
}

namespace {

// The output driver for `format`, refused when it writes no file.
GDALDriver* output_driver(const std::string& format) {
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(format.c_str());
  if (!driver) throw Error("unknown output format '" + format + "' (see gdalinfo --formats)");
  if (EQUAL(format.c_str(), "MEM")) throw Error("output format MEM writes no file; choose a file format");
  char** meta = driver->GetMetadata();
  if (!CSLFetchBoolean(meta, GDAL_DCAP_CREATECOPY, FALSE) && !CSLFetchBoolean(meta, GDAL_DCAP_CREATE, FALSE)) {
    throw Error("GDAL format '" + format + "' cannot write files");
  }
  return driver;
}

// Our defaults for the format, then the user's -co KEY=VALUE over them.
// `rows_at_once`: rows of every band a writer is handed at a time (0: no bound). A GeoTIFF tile row
// of every band is held until it is compressed, so the default tiles are no taller than that (16 to
// 256 rows, strips below 16) unless the user sets TILED or BLOCKYSIZE: with 256-row tiles,
// `skyview horizon --method sampled` at 1024 directions on 1000 columns held 1.2 GB, not 256 MB.
CPLStringList creation_options(const std::string& format, GDALDataType type, const std::vector<std::string>& user,
                               int rows_at_once = 0) {
  CPLStringList opts;
  // GeoTIFFs, cloud-optimised ones too (whose own default, LZW without a predictor, packs float bands
  // worse): DEFLATE with a predictor, compressed on as many threads as the run may use (--threads:
  // single-threaded DEFLATE was a tenth of skyview svf's wall time on a 2000 x 2000 raster with 2 cores).
  if (format == "GTiff" || format == "COG") {
    opts.SetNameValue("COMPRESS", "DEFLATE");
    opts.SetNameValue("BIGTIFF", "IF_SAFER");
    opts.SetNameValue("NUM_THREADS", run_threads_text().c_str());
  }
  if (format == "GTiff") {
    opts.SetNameValue("TILED", "YES");
    opts.SetNameValue("PREDICTOR", type == GDT_Float32 ? "3" : "2");
    // Bands are written one after another (BandWriter): with pixel interleaving every tile would
    // hold all bands and be compressed again as each band arrives.
    opts.SetNameValue("INTERLEAVE", "BAND");
  }
  if (format == "COG") opts.SetNameValue("PREDICTOR", "YES");  // COG picks the float predictor itself
  CPLStringList users;
  for (const auto& kv : user) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0) throw Error("creation option '" + kv + "' is not KEY=VALUE");
    users.SetNameValue(kv.substr(0, eq).c_str(), kv.substr(eq + 1).c_str());
  }
  if (format == "GTiff" && rows_at_once > 0 && rows_at_once < 256 && !users.FetchNameValue("TILED") &&
      !users.FetchNameValue("BLOCKYSIZE")) {
    if (rows_at_once < 16) opts.SetNameValue("TILED", "NO");
    opts.SetNameValue("BLOCKYSIZE", std::to_string(rows_at_once < 16 ? rows_at_once : rows_at_once / 16 * 16).c_str());
  }
  for (int i = 0; i < users.size(); ++i) {
    char* key = nullptr;
    const char* value = CPLParseNameValue(users[i], &key);
    if (key) opts.SetNameValue(key, value);
    CPLFree(key);
  }
  return opts;
}

// GDAL names the file it was writing, which is the temporary one: the user knows `path`.
std::string naming_output(std::string why, const std::string& tmp, const std::string& path) {
  for (const std::string& name : {tmp, std::filesystem::path(tmp).filename().string()}) {
    const std::string final_name = name == tmp ? path : std::filesystem::path(path).filename().string();
    for (std::size_t at = why.find(name); at != std::string::npos; at = why.find(name, at + final_name.size())) {
      why.replace(at, name.size(), final_name);
    }
  }
  return why;
}

// Closes a dataset written under `tmp`: GDAL 3.6 reports failures to flush only through the error
// state. Returns why it failed, or "".
std::string close_written(GDALDataset* ds) {
  std::string why = CPLGetLastErrorType() >= CE_Failure ? last_gdal_error() : "";
  GDALClose(ds);
  if (why.empty() && CPLGetLastErrorType() >= CE_Failure) why = last_gdal_error();
  return why;
}

// Removes a temporary output and its side files; a file the driver cannot open again (a failed
// Create leaves a bare header) is unlinked.
void remove_temporary(GDALDriver* driver, const std::string& tmp) {
  forget_temporary(tmp);
  if (!path_exists(tmp)) return;
  driver->Delete(tmp.c_str());
  if (path_exists(tmp)) VSIUnlink(tmp.c_str());
  CPLErrorReset();
}

// The finished temporary file replaces `path` (an old dataset there goes with its side files, so
// nothing stale survives).
void move_into_place(GDALDriver* driver, const std::string& tmp, const std::string& path) {
  if (path_exists(path)) {
    if (GDALDriver* old = GetGDALDriverManager()->GetDriverByName(driver->GetDescription());
        old && old->Delete(path.c_str()) != CE_None) {
      VSIUnlink(path.c_str());
    }
  }
  if (driver->Rename(path.c_str(), tmp.c_str()) != CE_None) {
    const std::string why = last_gdal_error();
    remove_temporary(driver, tmp);
    throw Error("cannot move the finished output into place at '" + path + "': " + why);
  }
  forget_temporary(tmp);
}

// Copies a finished memory dataset into `path` in `format`, under a temporary name first.
void commit_dataset(GDALDataset* mem, const std::string& path, const std::string& format,
                    const std::vector<std::string>& user_options, bool overwrite) {
  check_output_writable(path, overwrite);
  GDALDriver* driver = output_driver(format);
  const CPLStringList opts = creation_options(format, mem->GetRasterBand(1)->GetRasterDataType(), user_options);
  const std::string tmp = temporary_output_name(path);
  CPLErrorReset();
  GDALDataset* out = driver->CreateCopy(tmp.c_str(), mem, FALSE, opts.List(), nullptr, nullptr);
  const std::string why = out ? close_written(out) : last_gdal_error();
  if (!why.empty() || !out) {
    remove_temporary(driver, tmp);
    throw Error("cannot write '" + path + "': " + naming_output(why, tmp, path));
  }
  move_into_place(driver, tmp, path);
}

DatasetPtr make_memory_dataset(int width, int height, int bands, GDALDataType type) {
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  DatasetPtr ds(mem->Create("", width, height, bands, type, nullptr));
  if (!ds) throw Error("out of memory for a " + std::to_string(width) + "x" + std::to_string(height) + " output");
  return ds;
}

void set_georeference(GDALDataset* ds, const GeoReference& georef) {
  if (georef.has_geotransform) {
    double gt[6];
    std::copy(georef.geotransform.begin(), georef.geotransform.end(), gt);
    ds->SetGeoTransform(gt);
  }
  if (!georef.crs_wkt.empty()) ds->SetProjection(georef.crs_wkt.c_str());
}

// The band at `index`, or an internal error.
GDALRasterBand* band_of(GDALDataset* ds, int index, const std::string& path) {
  if (!ds || index < 0 || index >= ds->GetRasterCount()) {
    throw Error("band " + std::to_string(index + 1) + " of '" + path + "' cannot be written (internal error)");
  }
  return ds->GetRasterBand(index + 1);
}

// check_output_format's test of the name.
void check_output_name(const std::string& path, const std::string& format, GDALDriver* driver) {
  std::vector<std::string> extensions;
  std::istringstream names(driver->GetMetadataItem(GDAL_DMD_EXTENSIONS)  ? driver->GetMetadataItem(GDAL_DMD_EXTENSIONS)
                           : driver->GetMetadataItem(GDAL_DMD_EXTENSION) ? driver->GetMetadataItem(GDAL_DMD_EXTENSION)
                                                                         : "");
  for (std::string e; names >> e;) extensions.push_back(lowercase("." + e));
  if (extensions.empty()) return;  // the format names no extension
  if (std::find(extensions.begin(), extensions.end(), lowercase_extension(path)) != extensions.end()) return;
  std::string list;
  for (std::size_t i = 0; i < extensions.size(); ++i)
    list += (i == 0 ? "" : i + 1 == extensions.size() ? " or " : ", ") + extensions[i];
  throw Error("output '" + path + "' does not end in " + list + ", as GDAL format '" + format +
              "' names its files; rename it, or give -of for the format its name says");
}

}  // namespace

void check_output_format(const std::string& path, const std::string& format, int bands,
                         const std::vector<std::string>& user_options) {
  init_gdal();
  GDALDriver* driver = output_driver(format);
  check_output_name(path, format, driver);
  // A format that cannot hold float32 would round svf to bytes with only a GDAL warning.
  if (const char* types = driver->GetMetadataItem(GDAL_DMD_CREATIONDATATYPES);
      types && !std::strstr(types, "Float32")) {
    throw Error("GDAL format '" + format + "' cannot hold float32 values (it writes " + types +
                "); choose GTiff, COG, HFA or netCDF");
  }
  const CPLStringList opts = creation_options(format, GDT_Float32, user_options);
  // Try a 2 x 2 dataset of the run's bands in memory now, rather than fail at the end of the run:
  // formats that only copy a finished dataset check it then, and formats created band by band may
  // hold fewer bands than asked (SAGA and RST refuse more than one, GTX keeps one silently).
  const bool creates = CSLFetchBoolean(driver->GetMetadata(), GDAL_DCAP_CREATE, FALSE);
  // The format's extension (some drivers name only their files with it: SAGA's .sdat).
  std::string ext = driver->GetMetadataItem(GDAL_DMD_EXTENSION) ? driver->GetMetadataItem(GDAL_DMD_EXTENSION) : "";
  if (ext.empty() && driver->GetMetadataItem(GDAL_DMD_EXTENSIONS)) {
    std::istringstream first(driver->GetMetadataItem(GDAL_DMD_EXTENSIONS));
    first >> ext;
  }
  const std::string stem = "skyview-format-probe-" + std::to_string(::getpid());
  const std::string leaf = stem + "." + (ext.empty() ? "out" : ext);
  struct Probe {
    std::string why;  // empty when writing worked
    int kept = 0;     // bands a reader gets back
  };
  auto probe = [&](const std::string& name, int n) {
    Probe p{"", n};
    const CPLErrorHandlerPusher quiet(CPLQuietErrorHandler);  // the probe's warnings would only confuse
    CPLErrorReset();
    GDALDataset* out = nullptr;
    if (creates) {
      out = driver->Create(name.c_str(), 2, 2, n, GDT_Float32, opts.List());
    } else {
      DatasetPtr source = make_memory_dataset(2, 2, n, GDT_Float32);
      out = driver->CreateCopy(name.c_str(), source.get(), FALSE, opts.List(), nullptr, nullptr);
    }
    if (out) p.kept = std::min(p.kept, out->GetRasterCount());
    p.why = out ? close_written(out) : last_gdal_error();
    if (p.why.rfind(name + ": ", 0) == 0) p.why.erase(0, name.size() + 2);  // the probe's name means nothing here
    // Some formats (XYZ) keep the first band with only a warning: count what a reader gets back.
    if (out && p.why.empty()) {
      GDALDatasetUniquePtr back(GDALDataset::Open(name.c_str(), GDAL_OF_RASTER));
      if (back) p.kept = std::min(p.kept, back->GetRasterCount());
    }
    driver->Delete(name.c_str());
    VSIUnlink(name.c_str());
    CPLErrorReset();
    if (p.why.empty() && !out) p.why = "unknown GDAL error";
    return p;
  };
  // In memory; formats created band by band that cannot be created there at all (SAGA, netCDF: one
  // band fails too) in the temporary folder, and where one band fails there as well, not judged.
  std::error_code ec;
  const std::filesystem::path temp = std::filesystem::temp_directory_path(ec);
  std::vector<std::string> places{"/vsimem/" + leaf};
  if (creates && !ec) places.push_back((temp / leaf).string());
  std::optional<Probe> found;
  for (std::size_t i = 0; i < places.size() && !found; ++i) {
    const Probe all = probe(places[i], bands);
    if (all.why.empty() || !creates || probe(places[i], 1).why.empty()) found = all;
    // A failed creation can leave a header behind (SAGA's .sgrd), which Delete does not find.
    if (i == 0) continue;
    for (const auto& entry : std::filesystem::directory_iterator(temp, ec)) {
      if (entry.path().stem() == stem) std::filesystem::remove(entry.path(), ec);
    }
  }
  if (!found) return;
  const auto& [why, kept] = *found;
  // No bands at all: netCDF defines its variables as they are written, not judged here either.
  if (why.empty() && kept == 0) return;
  const std::string what = std::to_string(bands) + " float32 band" + (bands == 1 ? "" : "s");
  if (!why.empty()) throw Error("GDAL format '" + format + "' cannot write " + what + ": " + why);
  if (kept < bands) {
    throw Error("GDAL format '" + format + "' keeps " + std::to_string(kept) + " of " + what +
                "; choose a format that holds them all (GTiff, COG, HFA, netCDF)");
  }
}

// Formats that GDAL can create band by band are written in place under the temporary name; the
// others (PNG, COG ...) only copy a finished dataset, so they get a memory dataset copied at finish().
struct BandWriter::State {
  std::string path, tmp;
  int width = 0, height = 0;
  WriteOptions options;
  GDALDriver* driver = nullptr;
  DatasetPtr ds;
  bool direct = false;  // ds is the output under `tmp`, not a memory dataset
  std::vector<float> buffer;
};

BandWriter::BandWriter(const std::string& path, int width, int height, int bands, const GeoReference& georef,
                       const WriteOptions& options)
    : s_(std::make_unique<State>()) {
  init_gdal();
  if (bands < 1) throw Error("nothing to write to '" + path + "'");
  State& s = *s_;
  s.path = path;
  s.width = width, s.height = height;
  s.options = options;
  check_output_writable(path, options.overwrite);
  check_output_format(path, options.format, bands, options.creation_options);
  s.driver = output_driver(options.format);
  s.direct = CSLFetchBoolean(s.driver->GetMetadata(), GDAL_DCAP_CREATE, FALSE);
  if (s.direct) {
    const CPLStringList opts =
        creation_options(options.format, GDT_Float32, options.creation_options, options.rows_at_once);
    s.tmp = temporary_output_name(path);
    CPLErrorReset();
    s.ds.reset(s.driver->Create(s.tmp.c_str(), width, height, bands, GDT_Float32, opts.List()));
    if (!s.ds) {
      const std::string why = naming_output(last_gdal_error(), s.tmp, path);
      remove_temporary(s.driver, s.tmp);
      throw Error("cannot write '" + path + "': " + why);
    }
  } else {
    s.ds = make_memory_dataset(width, height, bands, GDT_Float32);
  }
  set_georeference(s.ds.get(), georef);
  for (const auto& [k, v] : options.metadata) s.ds->SetMetadataItem(k.c_str(), v.c_str());
}

BandWriter::~BandWriter() {
  if (!s_->ds) return;  // finished
  const bool on_disk = s_->direct;
  s_->ds.reset();
  if (on_disk) remove_temporary(s_->driver, s_->tmp);
}

void BandWriter::write(int index, const OutputBand& band) {
  write_rows(index, 0, s_->height, band.values);
  describe(index, band);
}

void BandWriter::write_rows(int index, int row0, int rows, const float* values) {
  State& s = *s_;
  GDALRasterBand* band = band_of(s.ds.get(), index, s.path);
  if (row0 < 0 || rows < 0 || row0 + rows > s.height) {
    throw Error("rows " + std::to_string(row0) + " to " + std::to_string(row0 + rows) + " of '" + s.path +
                "' are outside it (internal error)");
  }
  const std::size_t n = static_cast<std::size_t>(s.width) * rows;
  s.buffer.resize(std::max(s.buffer.size(), n));
  for (std::size_t i = 0; i < n; ++i) s.buffer[i] = std::isnan(values[i]) ? s.options.nodata : values[i];
  if (band->RasterIO(GF_Write, 0, row0, s.width, rows, s.buffer.data(), s.width, rows, GDT_Float32, 0, 0) != CE_None) {
    throw Error("cannot write band " + std::to_string(index + 1) + " of '" + s.path +
                "': " + naming_output(last_gdal_error(), s.tmp, s.path));
  }
}

void BandWriter::describe(int index, const OutputBand& src) {
  GDALRasterBand* band = band_of(s_->ds.get(), index, s_->path);
  band->SetNoDataValue(s_->options.nodata);
  band->SetDescription(src.description.c_str());
  band->SetUnitType(src.unit.c_str());
  for (const auto& [k, v] : src.metadata) band->SetMetadataItem(k.c_str(), v.c_str());
}

int BandWriter::block_rows() const {
  if (!s_->ds || !s_->direct) return 1;
  int x = 0, y = 0;
  s_->ds->GetRasterBand(1)->GetBlockSize(&x, &y);
  return std::max(1, y);
}

void BandWriter::finish() {
  State& s = *s_;
  if (!s.ds) throw Error("'" + s.path + "' is already finished (internal error)");
  if (!s.direct) {
    commit_dataset(s.ds.get(), s.path, s.options.format, s.options.creation_options, s.options.overwrite);
    s.ds.reset();
    return;
  }
  // netCDF variables are named after the bands once the file is closed (netcdf_names.cpp).
  const bool netcdf = EQUAL(s.driver->GetDescription(), "netCDF");
  std::vector<std::string> names;
  for (int b = 1; netcdf && b <= s.ds->GetRasterCount(); ++b)
    names.emplace_back(s.ds->GetRasterBand(b)->GetDescription());
  // ENVI's header describes the file by the name it was created under: the temporary one.
  std::vector<std::string> headers;
  if (EQUAL(s.driver->GetDescription(), "ENVI")) {
    const CPLStringList files(s.ds->GetFileList());
    for (int i = 0; i < files.size(); ++i) {
      if (lowercase_extension(files[i]) == ".hdr") headers.emplace_back(files[i]);
    }
  }
  std::string why = close_written(s.ds.release());
  for (const std::string& header : headers) {
    std::ifstream in(header);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    in.close();
    name_final_output(text, s.tmp, s.path);
    std::ofstream(header, std::ios::trunc) << text;
  }
  if (why.empty() && netcdf) {
    try {
      detail::name_netcdf_variables(s.tmp, s.path, names);
    } catch (const Error& e) {
      why = e.what();
    }
  }
  if (!why.empty()) {
    remove_temporary(s.driver, s.tmp);
    throw Error("cannot write '" + s.path + "': " + naming_output(why, s.tmp, s.path));
  }
  move_into_place(s.driver, s.tmp, s.path);
}

void write_bands(const std::string& path, int width, int height, const GeoReference& georef,
                 const std::vector<OutputBand>& bands, const WriteOptions& options) {
  BandWriter out(path, width, height, static_cast<int>(bands.size()), georef, options);
  for (std::size_t b = 0; b < bands.size(); ++b) out.write(static_cast<int>(b), bands[b]);
  out.finish();
}

void write_terrain(const std::string& path, const Terrain& t, const WriteOptions& options) {
  std::vector<float> z(t.heights.size());
  for (std::size_t i = 0; i < z.size(); ++i) z[i] = static_cast<float>(t.base_height + t.heights.values()[i]);
  write_bands(path, t.width(), t.height(), t.georef, {{"height", "metre", z.data(), {}}}, options);
}

void write_png(const std::string& path, int width, int height, int channels, const std::uint8_t* pixels,
               bool overwrite) {
  if (channels < 1 || channels > 4 || width < 1 || height < 1) {
    throw Error("cannot write the picture '" + path + "': " + std::to_string(width) + " x " + std::to_string(height) +
                " pixels of " + std::to_string(channels) + " channels (internal error)");
  }
  init_gdal();
  DatasetPtr ds = make_memory_dataset(width, height, channels, GDT_Byte);
  // Interleaved samples: pixel spacing `channels`, line spacing a row of them, band spacing 1.
  const GSpacing pixel = channels, line = static_cast<GSpacing>(width) * channels;
  if (ds->RasterIO(GF_Write, 0, 0, width, height, const_cast<std::uint8_t*>(pixels), width, height, GDT_Byte, channels,
                   nullptr, pixel, line, 1, nullptr) != CE_None) {
    throw Error("cannot build the picture '" + path + "'");
  }
  commit_dataset(ds.get(), path, "PNG", {}, overwrite);
}

void write_preview_png(const std::string& path, int width, int height, const float* values, double lo, double hi,
                       bool overwrite) {
  // Nodata is transparent (grey and alpha), not black: black is an svf of 0.
  const std::size_t n = static_cast<std::size_t>(width) * height;
  const int channels = std::any_of(values, values + n, [](float v) { return std::isnan(v); }) ? 2 : 1;
  std::vector<std::uint8_t> pixels(n * channels);
  const double scale = hi > lo ? 255.0 / (hi - lo) : 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double v = values[i];
    pixels[i * channels] =
        std::isnan(v) ? 0 : static_cast<std::uint8_t>(std::clamp((v - lo) * scale, 0.0, 255.0) + 0.5);
    if (channels == 2) pixels[i * 2 + 1] = std::isnan(v) ? 0 : 255;
  }
  write_png(path, width, height, channels, pixels.data(), overwrite);
}

}  // namespace skyview
