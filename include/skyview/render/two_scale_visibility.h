#pragma once
// Sky visibility and solar exposure of what a camera sees, the two-scale screen-space method of
// Munoz-Pandiella et al., "Solar exposure of complex cities" (Sections 5 and 6):
//
// - Large scale (Section 5.1): each visible point is taken into the zenithal depth map and the map
//   is marched in N directions (a per-pixel random rotation of an even set) with S samples each, at
//   distances growing geometrically from one texel to max_distance. A solid part of a sampled
//   texel that reaches down to the point's height raises the horizon h(θ) to the angle of its top;
//   while every sample from the point outwards has a solid part wholly above the point (the point
//   stands under a porch, a balcony, a bridge), the lowest angle of their bottoms is the opening
//   angle h'(θ), the upper end of the sky seen that way. An opening farther than
//   opening_max_distance is discarded (the direction is closed). Directions whose whole upper
//   half-plane lies behind the point's surface are not marched (the paper's cosine-based discard).
//   svf_large is the cosine-weighted sky fraction of the regions [h(θ), h'(θ)] on the pixel's
//   normal, each direction standing for a slice 2π/N wide.
// - Fine scale (Section 5.2): horizon-based ambient occlusion (Bavoil et al. 2008) on the camera's
//   buffers: in N screen directions, S samples within fine_radius metres; a sample that raises the
//   horizon above the tangent angle t(θ) adds W(r) (sin h − sin h_prev) with W(r) = 1 − r²/R²
//   (Eq. 6); svf_fine = 1 − the mean over directions.
// - Combination: `multiply`, the paper's: svf = svf_large · svf_fine and exposure = exposure_large ·
//   svf_fine. `intersect`, which the paper's discussion asks for: the fine scale is marched along the
//   same world directions in the camera's position buffer, its horizon raises h(θ), and svf and
//   exposure come from the intersected regions.
// - Exposure (Section 6): the regions sampled in the mip-mapped exposure map with the sampler of
//   Eqs. 7–10 (exposure_sampler.h), cosine-weighted on the pixel's normal.
#include <cstdint>
#include <optional>

#include "skyview/render/view_buffers.h"
#include "skyview/render/zenith_depth_map.h"
#include "skyview/sky/exposure_sampler.h"

namespace skyview {

enum class ScaleCombination { multiply, intersect };

struct TwoScaleOptions {
  int directions = 16;              // N_dir, both scales
  int samples = 16;                 // S_dir, both scales
  double max_distance = 300.0;      // metres marched in the zenith map
  double opening_max_distance = 0;  // metres; 0: no limit
  double fine_radius = 3.0;         // metres, the fine scale's reach
  ScaleCombination combine = ScaleCombination::multiply;
  bool fine_scale = true;  // false: the large scale alone (svf_fine = 1)
  std::uint64_t seed = 1;
};

struct TwoScaleBands {
  Grid<float> svf, svf_large, svf_fine;  // 1; NaN where the pixel sees sky
  Grid<float> exposure;                  // kWh m-2 over the map's period; empty without a sampler
  Grid<float> exposure_direct, exposure_diffuse;
};

// Throws skyview::UsageError for directions or samples below 1 or distances that are not finite
// and positive. `sampler`: the exposure map's, made with options.directions directions and
// rotation 0 (optional).
TwoScaleBands two_scale_visibility(const ViewBuffers& view, const Camera& camera, const ZenithDepthMap& zenith,
                                   const TwoScaleOptions& options, const ExposureSampler* sampler = nullptr);

// ∫ over elevations [low, high] of max(0, n·ω) cos e de for the azimuth whose horizontal unit vector
// makes `along` = n_h·u with the normal and `up` = n_z: the cosine-weighted sky of one direction
// (per radian of azimuth; times Δφ/π gives its share of the svf).
double cosine_weighted_slice(double along, double up, double low, double high);

}  // namespace skyview
