#pragma once
// One texel of the zenithal depth map: the solid parts a downward ray from `top` meets under the
// scene-local point (x, y), top down (zenith_depth_map.h has the rules). Shared by the full build
// and the update of a region (zenith_update.cpp).
#include <vector>

#include "skyview/render/zenith_depth_map.h"

namespace skyview {

std::vector<float> zenith_column(const Scene& scene, const RayScene& rays, float x, float y, float top,
                                 const ZenithOptions& o, bool& truncated);

}  // namespace skyview
