#pragma once
// The ray-cast reference of exposure in view (what the paper's Figure 10 compares against): per
// pixel, the exposure map's sky (direct and diffuse radiance integrated over its period, Wh m-2
// sr-1) integrated over the pixel's tilted hemisphere, E = ∫ L(ω) max(0, n·ω) V(ω) dΩ, with exact
// Embree visibility V. Monte Carlo with `rays` samples, each drawn by one of two strategies with
// equal odds and weighted by the balance heuristic (one-sample multiple importance sampling, Veach
// 1997): the cosine-weighted directions of the svf reference (density n·ω/π) and the map's own
// radiance (a cell with probability ∝ L·Ω, uniform within it: density L/T, T = ∑ L·Ω), so the sun's
// narrow track is found as surely as the broad sky. The estimator is unbiased for the map's
// piecewise-constant sky; its standard error is the sample standard deviation over sqrt(rays).
#include <cstdint>

#include "skyview/render/view_buffers.h"
#include "skyview/sky/exposure_map.h"

namespace skyview {

struct ExposureReference {
  Grid<float> exposure, stderr_;  // kWh m-2 over the map's period; NaN where the pixel sees sky
};

// Throws skyview::UsageError for rays < 1.
ExposureReference exposure_reference(const RayScene& scene, const ViewBuffers& view, const ExposureMap& map, int rays,
                                     std::uint64_t seed = 11);

}  // namespace skyview
