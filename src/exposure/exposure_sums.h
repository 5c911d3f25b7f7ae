#pragma once
// The per-cell sums of skyview exposure over a window, fed a direction (or a batch of them) at a
// time in order, as a horizon engine finds them: the sky through each direction's slice by the
// sampler, and for the exact method the sun of the steps between each pair of neighbouring
// directions against the horizon interpolated between them.
#include <memory>
#include <vector>

#include "exposure/sun_gaps.h"
#include "skyview/exposure/exposure.h"
#include "skyview/sky_view/sky_view.h"

namespace skyview::detail {

// What every window of a run shares.
struct ExposureSetup {
  ExposureMethod method = ExposureMethod::fast;
  std::unique_ptr<ExposureSampler> sampler;  // the map read per slice (exact: at full resolution)
  // The sky read per gap between two directions under the interpolated horizon (add_gap), as the
  // beam test reads it; otherwise per direction's slice under its constant horizon (the paper's).
  bool sky_by_gaps = true;
  int directions = 0;
  double rotation = 0.0;  // of the direction set (radians)
  // exact: the steps whose sun lies between direction k and the next.
  std::vector<SunGap> gaps;
  double albedo = 0.2;
  const Grid<float>* albedo_grid = nullptr;  // of the whole window computed
  double global_horizontal = 0.0;            // Wh/m², the map's unobstructed
};

class ExposureSums {
 public:
  ExposureSums(const Terrain& terrain, const Window& window, const ExposureSetup& setup);
  ~ExposureSums();
  ExposureSums(const ExposureSums&) = delete;
  ExposureSums& operator=(const ExposureSums&) = delete;
  // Directions [first, first + count) of the window's horizons, in order from 0, planes laid out
  // as in HorizonField; `field` for the cells' rotations.
  void add(int first, int count, const float* upper, const HorizonField& field);
  // Writes the window's cells into rows [row0, row0 + window rows) of `out` (kWh/m²), with the
  // sky-view products of the same horizons for the svf band and the reflected term.
  // `albedo_row0`: the window's first row in setup.albedo_grid.
  void finish(const SkyViewProducts& products, int row0, ExposureBands& out) const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace skyview::detail
