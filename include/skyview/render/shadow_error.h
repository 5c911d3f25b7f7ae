#pragma once
// A shadow method's error against exact shadow rays on the same receivers: the share whose sunlit
// state (visibility ≥ 0.5) is wrong, split into shadow edges and interiors, and into light leaking
// (sunlit where the rays see shadow) and acne (shadow where the rays see the sun). A receiver is at
// an edge when an exact ray from its plane `edge_texels` of the method's texel away, across the
// sun's rays (±u, ±v and the four diagonals of the light frame), sees the other state: within two
// texels of the shadow's boundary whatever the receivers' spacing.
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

// Compares `method` with `exact` (both from sun_visibility on `receivers` for `sun_direction`).
// Edges are found with the method's per-receiver texel (ShadowResult::texel); for an exact method,
// none. `options` gives the rays' offset.
ShadowError shadow_error(const RayScene& rays, Vec3f sun_direction, const ShadowReceivers& receivers,
                         const ShadowResult& exact, const ShadowResult& method, const ShadowOptions& options = {},
                         double edge_texels = 2.0);

}  // namespace skyview
