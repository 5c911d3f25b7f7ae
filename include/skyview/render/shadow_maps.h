#pragma once
// Sun shadows on given receiver points (the surface points a camera sees): by exact shadow rays
// (Embree) and by the shadow-map family of the hybrid shadow maps paper (Kolivand & Sunar,
// ../shared/papers/hybrid-shadow-maps-outdoor.txt): a plain depth map with percentage-closer
// filtering (PCF), variance shadow maps (VSM, Donnelly & Lauritzen 2006), layered VSM (LVSM,
// Lauritzen & McCool 2008), cascaded shadow maps (CSM) with practical splits, and the paper's hybrid
// (HSM): layered variance maps over cascades split logarithmically. docs/shadows.md has the formulas,
// the defaults and each method's measured error against the exact rays.
//
// Depth maps are rendered with Embree too: orthographic rays along the sun's direction over the
// receivers' light-space bounds (the part of the scene the view needs), so the maps differ from
// the exact rays only by sampling and filtering, never by a second copy of the geometry.
// Coordinates are the scene's (relative to Scene::origin, metres, x east, y north, z up).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "skyview/scene/ray_scene.h"
#include "skyview/scene/scene.h"

namespace skyview {

// World points seen by a camera and their surfaces' unit normals (for the offset of shadow rays and
// the slope-scaled bias of maps; empty: no normals, points are offset straight up and unbiased by
// slope). A receiver whose normal faces away from the sun is in its own shadow for every method.
struct ShadowReceivers {
  std::vector<Vec3f> points;
  std::vector<Vec3f> normals;
};

enum class ShadowMethod { exact, pcf, vsm, lvsm, csm, hsm };

// "exact", "pcf", ...; parse_shadow_method throws UsageError naming the choices.
std::string shadow_method_name(ShadowMethod method);
ShadowMethod parse_shadow_method(const std::string& name);

struct ShadowOptions {
  // Texels on the longer side of each light-space map (the paper measures at 1024 x 1024). Texels
  // are square; the shorter side gets as many as the receivers' bounds need.
  int map_size = 1024;
  // Taps on a side of the filter (PCF samples, VSM/LVSM/HSM moment window), each tap bilinear: the
  // footprint is kernel + 1 texels wide. Odd. The paper gives none; 3 is the common choice.
  int pcf_kernel = 3;
  // VSM: the least variance (m²) in Chebyshev's bound, against acne on flat receivers, and the
  // light-bleeding reduction (Lauritzen, GPU Gems 3 ch. 8: the bound's lower share cut off and
  // the rest rescaled; 0 off). Not given by the paper.
  double min_variance = 1e-4;
  double light_bleed_reduction = 0.2;
  // LVSM and HSM: depth layers (per cascade for HSM). The paper's table 2 runs LVSM with 8 and HSM
  // with 7 for the same quality.
  int layers = 8;
  int hsm_layers = 7;
  // LVSM and HSM: how far before its layer a receiver's warp starts, as a share of the layer's
  // depth: the paper's overlapping layers [s_i, s_{i+1} + eps] ("medium bounding"), seen from the
  // next layer. Without it a receiver just behind a layer's front sits as close to the occluders
  // clamped there as to its own surface, and light leaks.
  double layer_overlap = 0.5;
  // CSM and HSM: cascades over the receivers' distance from `eye` (the paper's three classes A, B, C).
  int cascades = 3;
  // Split i of C at lambda·n·(f/n)^(i/C) + (1 − lambda)·(n + (f − n)·i/C) (Zhang et al.'s practical
  // split; 1: logarithmic). CSM uses split_lambda, HSM the paper's logarithmic split.
  double split_lambda = 0.5;
  double hsm_split_lambda = 1.0;
  std::optional<Vec3f> eye;  // the camera's position; CSM and HSM need it
  // Depth bias of map lookups: constant (m) plus slope-scaled (texels times tan of the sun's angle
  // to the normal, capped at 10 texels).
  double depth_bias = 0.05;
  double slope_bias = 1.0;
  // Exact rays start this far (m) off the surface along its normal.
  double ray_offset = 0.01;
  // Exact: the visible share of the sun's disc (0.53° wide) from soft_samples stratified
  // directions (a square number) instead of its centre alone.
  bool soft = false;
  int soft_samples = 64;
  double sun_angular_radius = 0.2665 * 3.14159265358979323846 / 180.0;
  // Memory the light-space maps may take (bytes); more is refused.
  std::size_t max_map_bytes = std::size_t{1} << 31;
};

// Checks `options` for `method` (counts at least one, a map size within 1 .. the memory limit, an
// eye for CSM and HSM): UsageError, one line naming the option.
void validate_shadow_options(ShadowMethod method, const ShadowOptions& options);

struct ShadowResult {
  std::vector<float> visibility;  // per receiver, 0 (shadow) .. 1 (sunlit): filtered or the disc's share
  std::vector<float> texel;       // per receiver, the side (m) of the map texel it was looked up in; 0 exact
  double map_seconds = 0.0;       // rendering the light-space maps
  double lookup_seconds = 0.0;    // shadow rays, or filtering the maps at the receivers
  std::size_t map_bytes = 0;      // memory of the maps
  int maps = 0;                   // depth maps rendered (cascades)
  double seconds() const { return map_seconds + lookup_seconds; }
};

// Visibility of the sun from every receiver; `sun_direction` points towards the sun (need not be
// unit). Throws skyview::Error naming the sun's elevation when it is not above the horizon, and
// UsageError for bad options or receivers (normals neither empty nor one per point).
ShadowResult sun_visibility(const RayScene& rays, const Scene& scene, Vec3f sun_direction,
                            const ShadowReceivers& receivers, ShadowMethod method, const ShadowOptions& options = {});

// A unit vector towards the sun at `azimuth` (radians clockwise from north, the scene's +y) and
// `elevation` (radians).
Vec3f sun_direction_of(double azimuth, double elevation);

}  // namespace skyview
