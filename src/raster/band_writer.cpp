// The band writer: a float32 raster written a band (or a block of rows) at a time under a
// temporary name, renamed into place by finish().
#include <cpl_string.h>
#include <gdal_priv.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "raster/gdal_common.h"
#include "raster/netcdf_names.h"
#include "skyview/core/error.h"
#include "skyview/core/lowercase.h"
#include "skyview/raster/band_writer.h"
#include "skyview/raster/output_checks.h"
#include "skyview/raster/raster_read.h"
#include "skyview/raster/temporary_outputs.h"

namespace skyview {

using namespace detail;

namespace {

// The band at `index`, or an internal error.
GDALRasterBand* band_of(GDALDataset* ds, int index, const std::string& path) {
  if (!ds || index < 0 || index >= ds->GetRasterCount()) {
    throw Error("band " + std::to_string(index + 1) + " of '" + path + "' cannot be written (internal error)");
  }
  return ds->GetRasterBand(index + 1);
}

}  // namespace

// Formats that GDAL can create band by band are written in place under the temporary name; the
// others (PNG, COG ...) only copy a finished dataset, so they get a memory dataset copied at finish().
// A cloud-optimised GeoTIFF, which a city-scale run writes, is staged in a temporary GeoTIFF on disk
// instead (a memory dataset would hold the whole raster) and copied by GDAL's COG driver, which adds
// the overviews.
struct BandWriter::State {
  std::string path, tmp;
  int width = 0, height = 0;
  WriteOptions options;
  GDALDriver* driver = nullptr;
  DatasetPtr ds;
  bool direct = false;  // ds is the output under `tmp`, not a memory dataset
  std::string staging;  // where ds is a temporary GeoTIFF to be copied at finish() (COG)
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
  } else if (EQUAL(s.driver->GetDescription(), "COG")) {
    const std::filesystem::path target(path);
    s.staging = temporary_output_name((target.parent_path() / (target.stem().string() + ".staging.tif")).string());
    GDALDriver* gtiff = output_driver("GTiff");
    const CPLStringList opts = creation_options("GTiff", GDT_Float32, {}, options.rows_at_once);
    CPLErrorReset();
    s.ds.reset(gtiff->Create(s.staging.c_str(), width, height, bands, GDT_Float32, opts.List()));
    if (!s.ds) {
      const std::string why = naming_output(last_gdal_error(), s.staging, path);
      remove_temporary(gtiff, s.staging);
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
  if (!s_->staging.empty()) remove_temporary(output_driver("GTiff"), s_->staging);
}

void BandWriter::write(int index, const OutputBand& band) {
  write_rows(index, 0, s_->height, band.values);
  describe(index, band);
}

void BandWriter::write_rows(int index, int row0, int rows, const float* values) {
  write_window(index, 0, row0, s_->width, rows, values);
}

void BandWriter::write_window(int index, int col0, int row0, int cols, int rows, const float* values) {
  State& s = *s_;
  GDALRasterBand* band = band_of(s.ds.get(), index, s.path);
  if (col0 < 0 || row0 < 0 || cols < 0 || rows < 0 || col0 + cols > s.width || row0 + rows > s.height) {
    throw Error("cells (" + std::to_string(col0) + ", " + std::to_string(row0) + ") to (" +
                std::to_string(col0 + cols) + ", " + std::to_string(row0 + rows) + ") of '" + s.path +
                "' are outside it (internal error)");
  }
  const std::size_t n = static_cast<std::size_t>(cols) * rows;
  s.buffer.resize(std::max(s.buffer.size(), n));
  for (std::size_t i = 0; i < n; ++i) s.buffer[i] = std::isnan(values[i]) ? s.options.nodata : values[i];
  if (band->RasterIO(GF_Write, col0, row0, cols, rows, s.buffer.data(), cols, rows, GDT_Float32, 0, 0) != CE_None) {
    throw Error("cannot write band " + std::to_string(index + 1) + " of '" + s.path +
                "': " + naming_output(last_gdal_error(), s.tmp, s.path));
  }
}

void BandWriter::set_metadata(const std::map<std::string, std::string>& items) {
  if (!s_->ds) throw Error("'" + s_->path + "' is already finished (internal error)");
  for (const auto& [k, v] : items) s_->ds->SetMetadataItem(k.c_str(), v.c_str());
}

void BandWriter::describe(int index, const OutputBand& src) {
  GDALRasterBand* band = band_of(s_->ds.get(), index, s_->path);
  band->SetNoDataValue(s_->options.nodata);
  band->SetDescription(src.description.c_str());
  band->SetUnitType(src.unit.c_str());
  for (const auto& [k, v] : src.metadata) band->SetMetadataItem(k.c_str(), v.c_str());
}

int BandWriter::block_rows() const {
  if (!s_->ds || (!s_->direct && s_->staging.empty())) return 1;
  int x = 0, y = 0;
  s_->ds->GetRasterBand(1)->GetBlockSize(&x, &y);
  return std::max(1, y);
}

void BandWriter::finish() {
  State& s = *s_;
  if (!s.ds) throw Error("'" + s.path + "' is already finished (internal error)");
  if (!s.direct) {
    if (!s.staging.empty()) s.ds->FlushCache();
    try {
      commit_dataset(s.ds.get(), s.path, s.options.format, s.options.creation_options, s.options.overwrite);
    } catch (const Error&) {
      if (!s.staging.empty()) {
        s.ds.reset();
        remove_temporary(output_driver("GTiff"), s.staging);
      }
      throw;
    }
    s.ds.reset();
    if (!s.staging.empty()) remove_temporary(output_driver("GTiff"), s.staging);
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

}  // namespace skyview
