#pragma once
// Mip-map pyramid of an exposure map for the per-surface exposure sampler (Section 6 of the
// solar-exposure paper): level k merges 2^k × 2^k cells. Each block stores its exposure times
// solid angle (Wh/m², the block's energy on a surface facing it) and its solid-angle-weighted
// mean direction, so a region is integrated by summing blocks with one cosine per block. It also
// stores each band's first moment Σ value·Ω·ω: for a normal n that faces every direction of a
// block, the block's cosine-weighted exposure is exactly n·moment (the sampler's cosine,
// exposure_sampler.h).
#include <span>
#include <vector>

#include "skyview/sky/exposure_map.h"

namespace skyview {

class ExposurePyramid {
 public:
  struct Level {
    int width = 0, height = 0;
    std::vector<double> direct, diffuse;                   // Σ value·Ω over the block (Wh/m²)
    std::vector<double> solid_angle;                       // Σ Ω (sr)
    std::vector<Direction> centre;                         // unit mean direction
    std::vector<Direction> direct_moment, diffuse_moment;  // Σ value·Ω·ω (Wh/m² times a direction)
  };

  explicit ExposurePyramid(const ExposureMap& map);

  int levels() const { return static_cast<int>(levels_.size()); }
  const Level& level(int k) const { return levels_.at(k); }

  // Σ over blocks of level k whose centre is above `horizon` (as in ExposureMap::irradiation) of
  // block energy × max(0, n·centre). Level 0 equals ExposureMap::irradiation; coarser levels
  // trade accuracy (the cosine and the horizon test are taken at the block centre) for speed.
  double irradiation(ExposureBand b, const Direction& normal, std::span<const float> horizon, int level) const;

 private:
  std::vector<Level> levels_;
};

}  // namespace skyview
