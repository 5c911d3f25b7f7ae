// Writing outputs through GDAL under a temporary name beside the target, renamed into place once
// complete (raster_io.h): the format's creation options, closing and checking a written dataset,
// removing a failed one, and the small outputs that are not result rasters (reports, pictures).
#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <cpl_vsi.h>
#include <gdal_priv.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "raster/gdal_common.h"
#include "skyview/core/error.h"
#include "skyview/raster/output_checks.h"
#include "skyview/raster/output_files.h"
#include "skyview/raster/raster_read.h"
#include "skyview/raster/temporary_outputs.h"

namespace skyview {

namespace detail {

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
                               int rows_at_once) {
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
    // DEFLATE's fastest level: lossless like the rest, 4% larger than GDAL's default level 6 on the
    // five float bands of skyview svf at 1000 x 1000, and 0.2 of its 1.7 CPU-s faster (Dec 7).
    opts.SetNameValue("ZLEVEL", "1");
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

}  // namespace detail

using namespace detail;

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

}  // namespace skyview
