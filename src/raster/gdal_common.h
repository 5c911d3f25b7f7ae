#pragma once
// What the raster readers and writers share inside the library: GDAL's datasets as owned
// pointers, its last message, and the steps of writing an output under a temporary name and
// moving it into place (raster_io.h says why outputs are written so).
#include <cpl_string.h>
#include <gdal_priv.h>

#include <memory>
#include <string>
#include <vector>

#include "skyview/raster/georeference.h"

namespace skyview::detail {

struct DatasetCloser {
  void operator()(GDALDataset* ds) const { GDALClose(ds); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

bool path_exists(const std::string& path);
// GDAL's last message, or `otherwise` where it said nothing.
std::string last_gdal_error(const char* otherwise = "unknown GDAL error");
// The threads the run may use (--threads), as GDAL's options want them: GDAL decodes and compresses
// blocks on its own threads, outside oneTBB's pool.
std::string run_threads_text();

// The output driver for `format`, refused when it writes no file.
GDALDriver* output_driver(const std::string& format);
// Our defaults for the format, then the user's -co KEY=VALUE over them (gdal_output.cpp says which).
CPLStringList creation_options(const std::string& format, GDALDataType type, const std::vector<std::string>& user,
                               int rows_at_once = 0);
// GDAL names the file it was writing, which is the temporary one: the user knows `path`.
std::string naming_output(std::string why, const std::string& tmp, const std::string& path);
// Closes a dataset written under a temporary name; returns why it failed, or "".
std::string close_written(GDALDataset* ds);
// Removes a temporary output and its side files.
void remove_temporary(GDALDriver* driver, const std::string& tmp);
// The finished temporary file replaces `path`.
void move_into_place(GDALDriver* driver, const std::string& tmp, const std::string& path);
// Copies a finished memory dataset into `path` in `format`, under a temporary name first.
void commit_dataset(GDALDataset* mem, const std::string& path, const std::string& format,
                    const std::vector<std::string>& user_options, bool overwrite);
DatasetPtr make_memory_dataset(int width, int height, int bands, GDALDataType type);
void set_georeference(GDALDataset* ds, const GeoReference& georef);

}  // namespace skyview::detail
