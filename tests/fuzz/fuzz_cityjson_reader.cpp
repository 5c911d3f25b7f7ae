// libFuzzer target for the CityJSON reader (src/scene/cityjson_reader.cpp): city models come from
// anywhere, so every malformed document, vertex, index or template must end in a skyview::Error or
// a counted skip. Only skyview::Error is caught here: any other exception, crash, sanitizer report,
// hang or runaway allocation is a finding. Run it with scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_scene_support.h"
#include "scene/scene_input.h"
#include "skyview/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    skyview::SceneLoadOptions options;
    if (size > 0 && data[0] == '2') options.lod = "2";  // both ways of choosing a level of detail
    const auto input =
        skyview::open_cityjson_text(std::string(reinterpret_cast<const char*>(data), size), "fuzz", options);
    skyview::fuzz::add_to_scene(*input);
  } catch (const skyview::Error&) {
    // The documented way to reject a bad file.
  }
  return 0;
}
