#pragma once
// A shadow method's error against exact shadow rays on the same receivers: the share whose sunlit
// state (visibility ≥ 0.5) is wrong, split into shadow edges (receivers within `edge_texels` of the
// method's texel from a receiver of the other exact state) and interiors, and into light leaking
// (sunlit where the rays see shadow) and acne (shadow where the rays see the sun).
#include <cstddef>
#include <vector>

#include "skyview/render/shadow_maps.h"

namespace skyview {

struct ShadowError {
  std::size_t receivers = 0;
  std::size_t edge_receivers = 0;  // near a boundary of the exact shadow
  std::size_t wrong = 0, wrong_edge = 0, wrong_interior = 0;
  std::size_t leaks = 0, acne = 0;  // wrong = leaks + acne
  double mean_abs = 0.0;            // mean |visibility − exact visibility|

  double share(std::size_t n) const { return receivers ? static_cast<double>(n) / receivers : 0.0; }
  double wrong_share() const { return share(wrong); }
};

// Compares `method` with `exact` (both from sun_visibility on `receivers`). Edges are found with
// the method's per-receiver texel (ShadowResult::texel); for an exact method, none.
ShadowError shadow_error(const ShadowReceivers& receivers, const ShadowResult& exact, const ShadowResult& method,
                         double edge_texels = 2.0);

}  // namespace skyview
