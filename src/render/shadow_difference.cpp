// Agreement in grey, leaks in red, acne in blue.
#include "skyview/render/shadow_difference.h"

#include <algorithm>
#include <cmath>

#include "skyview/core/error.h"

namespace skyview {

std::vector<std::uint8_t> shadow_difference_picture(std::span<const float> method, std::span<const float> exact) {
  if (method.size() != exact.size()) throw Error("shadow_difference_picture: the two visibilities differ in size");
  std::vector<std::uint8_t> rgb(3 * method.size());
  for (std::size_t i = 0; i < method.size(); ++i) {
    const std::uint8_t* c = kDiffSky;
    if (!std::isnan(method[i]) && !std::isnan(exact[i])) {
      const bool lit = method[i] >= 0.5f, truly = exact[i] >= 0.5f;
      c = lit == truly ? (lit ? kDiffSunlit : kDiffShadow) : (lit ? kDiffLeak : kDiffAcne);
    }
    std::copy(c, c + 3, rgb.begin() + 3 * i);
  }
  return rgb;
}

}  // namespace skyview
