// libFuzzer target for the hand-written LAS reader (skyview/las_file.h). LAS files come from
// anywhere, so the reader must turn every malformed header, (E)VLR or record count into a
// skyview::Error. Only that exception is caught here: any other exception, crash, sanitizer
// report, hang or runaway allocation is a finding. Run it with scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "skyview/core/error.h"
#include "skyview/dsm/las_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const skyview::LasReader reader = skyview::LasReader::open_memory(data, size, "fuzz");
    volatile double sum = 0;
    volatile unsigned bits = 0;
    reader.read_points(
        [&](const std::vector<skyview::LasPoint>& points) {
          for (const skyview::LasPoint& p : points) {
            sum = sum + p.x + p.y + p.z;
            bits = bits ^ p.intensity ^ p.return_number ^ p.number_of_returns ^ p.classification;
          }
        },
        1000);
  } catch (const skyview::Error&) {
    // The documented way to reject a bad file.
  }
  return 0;
}
