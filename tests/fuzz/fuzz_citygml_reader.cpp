// libFuzzer target for the CityGML path (src/scene/citygml_reader.cpp over libcitygml and Xerces):
// whatever the XML, our walk over the parsed model (nested geometries, implicit geometries, rings,
// levels of detail) must end in a skyview::Error or a counted skip. Only skyview::Error is caught
// here: any other exception, crash, sanitizer report, hang or runaway allocation is a finding.
// Run it with scripts/fuzz.sh.
#include <cstddef>
#include <cstdint>
#include <string>

#include "scene/scene_input.h"
#include "skyview/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto input = skyview::open_citygml_text(std::string(reinterpret_cast<const char*>(data), size), "fuzz", {});
    skyview::Scene scene;
    skyview::SceneAssembly assembly(scene);
    assembly.begin_input({"fuzz", input->format(), input->declared_crs()}, nullptr);
    input->add_to(assembly);
    assembly.end_input();
    (void)input->extent();
  } catch (const skyview::Error&) {
    // The documented way to reject a bad file.
  }
  return 0;
}
