// libFuzzer target for the far field's pyramid files (skyview/tiling/pyramid_file.h): a tiles folder
// holds one that a rerun reads back, and a folder can hold anything. Every malformed file must end
// in a skyview::Error or levels whose sizes match the raster's; any other exception, crash,
// sanitizer report, hang or runaway allocation is a finding. Each input is decoded twice: as it
// is, and with its last 8 bytes made the checksum of the rest, so that mutations reach the checks
// behind the checksum. Run it with scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "skyview/core/error.h"
#include "skyview/tiling/pyramid_file.h"

namespace {

void decode(const std::string& bytes) {
  try {
    std::string source;
    const skyview::PyramidLevels p = skyview::decode_pyramid(bytes, "fuzz", &source);
    volatile double sum = p.lowest + p.highest + static_cast<double>(source.size());
    for (const skyview::Grid<float>& g : p.max) sum = sum + g.values().front() + g.values().back();
  } catch (const skyview::Error&) {
    // The documented way to reject a bad file.
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  decode(bytes);
  if (bytes.size() >= 8) {
    std::uint64_t sum = std::strtoull(skyview::pyramid_checksum(bytes).c_str(), nullptr, 16);
    for (int i = 0; i < 8; ++i) bytes[bytes.size() - 8 + i] = static_cast<char>((sum >> (8 * i)) & 0xff);
    decode(bytes);
  }
  return 0;
}
