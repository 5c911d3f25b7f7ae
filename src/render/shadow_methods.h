#pragma once
// The methods behind sun_visibility (shadow_maps.cpp dispatches, validates and times them).
#include <vector>

#include "render/shadow_light_space.h"

namespace skyview::detail {

// Exact shadow rays towards the sun's centre, or the visible share of its disc (options.soft).
std::vector<float> exact_visibility(const RayScene& rays, const Vec3& sun, const ShadowReceivers& receivers,
                                    const ShadowOptions& options);

// One map over all receivers: pcf, vsm or lvsm. Fills visibility, texel and the map's cost.
void single_map_visibility(const RayScene& rays, const LightFrame& frame, const std::vector<LightReceiver>& receivers,
                           ShadowMethod method, const ShadowOptions& options, ShadowResult& out);

// One map per cascade of the receivers' distance from the eye: csm (PCF in each) or hsm (layered
// variance maps in each).
void cascaded_visibility(const RayScene& rays, const LightFrame& frame, const std::vector<LightReceiver>& receivers,
                         const std::vector<Vec3f>& points, ShadowMethod method, const ShadowOptions& options,
                         ShadowResult& out);

// Split distances c_0 = near < c_1 < ... < c_C = far: lambda·near·(far/near)^(i/C) + (1 − lambda)·
// (near + (far − near)·i/C).
std::vector<double> cascade_splits(double near, double far, int cascades, double lambda);

}  // namespace skyview::detail
