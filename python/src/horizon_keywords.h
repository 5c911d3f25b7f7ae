#pragma once
// The horizon options as skyview.svf, skyview.horizon and skyview.exposure take them (the command
// line's names without dashes), onto the library's HorizonRequest.
#include <cstdint>
#include <optional>
#include <string>

#include "skyview/sky_view/horizon_request.h"

namespace skyview::python {

// None leaves the command line's default and, like an option not typed, is not "given" (an
// option the run would not use is refused only where given).
struct HorizonKeywords {
  std::optional<std::string> method;
  std::optional<int> directions, samples, far_lines, rays;
  std::optional<double> radius, refraction, max_error;
  std::optional<std::uint64_t> seed;
  std::optional<std::string> edge, curvature, azimuth_origin, azimuths;
  bool early_exit = true;
};

// Checks what CLI11 checks on the command line, then sets the keywords given (the method under
// r.method_option: --method, or exposure's --horizon-method).
void apply(HorizonRequest& r, const HorizonKeywords& k);

}  // namespace skyview::python
