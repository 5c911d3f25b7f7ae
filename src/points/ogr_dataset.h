#pragma once
// What the point table's reader and writer share of GDAL/OGR: an owning dataset pointer and GDAL's
// last error as the tail of a message.
#include <cpl_error.h>
#include <gdal_priv.h>

#include <memory>
#include <string>

namespace skyview::detail {

struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(d); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

// ": GDAL's message", or nothing when it left none.
inline std::string last_gdal_error() {
  const char* m = CPLGetLastErrorMsg();
  return m && *m ? std::string(": ") + m : std::string();
}

}  // namespace skyview::detail
