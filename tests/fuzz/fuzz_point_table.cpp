// libFuzzer target for the points `skyview points` reads (skyview/points/point_table.h): CSV files
// from anywhere, parsed by OGR's CSV driver and then here (coordinate columns found by name, cells
// parsed as numbers, bad rows kept with their reason). Every malformed file must end in a
// skyview::Error or a table; any other exception, crash, sanitizer report or hang is a finding.
// Run it with scripts/fuzz.sh.
#include <cpl_vsi.h>
#include <gdal.h>

#include <cstddef>
#include <cstdint>

#include "fuzz_gdal_setup.h"
#include "skyview/core/error.h"
#include "skyview/points/point_table.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const char* path = "/vsimem/fuzz_points.csv";
  VSIFCloseL(VSIFileFromMemBuffer(path, const_cast<GByte*>(data), size, FALSE));
  try {
    skyview::PointTable t = skyview::read_point_table(path, {}, "");
    volatile double sum = 0;
    for (const skyview::PointRow& r : t.rows) sum = sum + r.x + r.y + static_cast<double>(r.values.size());
  } catch (const skyview::Error&) {
    // The documented way to reject a bad table.
  }
  VSIUnlink(path);
  return 0;
}
