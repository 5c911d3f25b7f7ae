// libFuzzer target for the CityGML path (src/scene/citygml_reader.cpp over libcitygml and Xerces):
// whatever the XML, our walk over the parsed model (nested geometries, implicit geometries, rings,
// levels of detail) must end in a skyview::Error or a counted skip. Only skyview::Error is caught
// here: any other exception, crash, sanitizer report, hang or runaway allocation is a finding.
// Run it with scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_scene_support.h"
#include "scene/scene_input.h"
#include "skyview/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto input = skyview::open_citygml_text(std::string(reinterpret_cast<const char*>(data), size), "fuzz", {});
    skyview::fuzz::add_to_scene(*input);
  } catch (const skyview::Error&) {
    // The documented way to reject a bad file.
  }
  return 0;
}
