#pragma once
// The ray-cast reference the screen-space estimates are judged by (the paper's ground truth,
// Figure 5): per pixel, `rays` cosine-weighted directions about the pixel's normal cast with
// Embree; the svf is the fraction that reaches the sky (above the horizon, unoccluded), its
// standard error the binomial sqrt(p(1 − p)/rays).
#include <cstdint>

#include "skyview/render/view_buffers.h"

namespace skyview {

struct SvfReference {
  Grid<float> svf, stderr_;  // 1; NaN where the pixel sees sky
};

// Throws skyview::UsageError for rays < 1.
SvfReference svf_reference(const RayScene& scene, const ViewBuffers& view, int rays, std::uint64_t seed = 7);

}  // namespace skyview
