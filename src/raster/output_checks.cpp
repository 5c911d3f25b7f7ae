// Checks made on outputs before any computation, so that a run never fails, rounds or loses bands
// only at its end: the path is writable, the format can hold the bands, no output is an input.
#include <cpl_error.h>
#include <cpl_string.h>
#include <cpl_vsi.h>
#include <gdal_priv.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <optional>
#include <sstream>

#include "raster/gdal_common.h"
#include "skyview/core/error.h"
#include "skyview/core/lowercase.h"
#include "skyview/raster/output_checks.h"
#include "skyview/raster/raster_read.h"

namespace skyview {

using namespace detail;

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

}  // namespace skyview
