// The large-scale pass of Muñoz-Pandiella et al. (section 5.1 of "Solar exposure of complex
// cities"): N directions, S samples each, the direction set randomly rotated per cell as in
// horizon-based ambient occlusion (Bavoil, Sainz & Dimitrov 2008) to trade banding for noise.
// Samples are spaced quadratically, d_j = R ((j+1)/S)^2, so that near terrain, which moves the
// angle most, is sampled densely.
#include <cmath>
#include <sstream>
#include <vector>

#include "methods.h"
#include "ray_scan.h"
#include "skyview/core/error.h"
#include "skyview/core/number_text.h"

namespace skyview::detail {
namespace {

struct FixedDistances {
  static constexpr bool kDenseSteps = false;
  std::vector<double> distance, inverse;
  template <class Visit>
  void walk(double, double, double, double, double max_distance, double curvature, Visit&& visit) const {
    const std::size_t n = distance.size();
    for (std::size_t j = 0; j < n && distance[j] <= max_distance; ++j) {
      const double next = visit(distance[j], inverse[j], curvature * distance[j] * distance[j]);
      if (next < 0.0) return;
      while (j + 1 < n && distance[j + 1] <= next) ++j;
    }
  }
};

class SampledEngine final : public HorizonEngine {
 public:
  explicit SampledEngine(const HorizonParams& p) : p_(p) {
    if (p_.radius == 0.0) p_.radius = 500.0;
    if (p_.samples == 0) p_.samples = 16;
    if (p_.samples < 1 || p_.samples > 100000) throw UsageError("--samples must be between 1 and 100000");
    for (int j = 0; j < p_.samples; ++j) {
      const double f = (j + 1.0) / p_.samples;
      samples_.distance.push_back(p_.radius * f * f);
      samples_.inverse.push_back(1.0 / samples_.distance.back());
    }
  }
  std::string_view name() const override { return "sampled"; }
  std::string_view citation() const override {
    return "Munoz-Pandiella et al., Solar exposure of complex cities, sec. 5.1; per-cell rotation after Bavoil, "
           "Sainz & Dimitrov 2008 (HBAO)";
  }
  std::map<std::string, std::string> describe() const override {
    return {{"METHOD", "sampled"},
            {"DIRECTIONS", std::to_string(p_.directions)},
            {"SAMPLES", std::to_string(p_.samples)},
            {"RADIUS_M", number_text(p_.radius)},
            {"SEED", std::to_string(p_.seed)},
            {"SAMPLE_SPACING", "quadratic: d_j = R*((j+1)/S)^2"}};
  }
  double radius() const override { return p_.radius; }
  const HorizonParams& params() const override { return p_; }
  void compute_window(const Terrain& terrain, const Window& window, HorizonField& out,
                      ProgressCounter& progress) const override {
    // Rays stop at the raster's edge, but the samples are spread up to the radius: with none
    // inside the raster (a radius of 1e30 m) every cell would see an open sky.
    const double extent = ground_diagonal(terrain);
    if (samples_.distance.front() > extent) {
      std::ostringstream why;
      why << "--radius " << p_.radius << " m puts every sample of the sampled method beyond the raster (" << extent
          << " m across); give a radius within it";
      throw Error(why.str());
    }
    ScanSettings s = scan_settings(p_, terrain);
    s.rotate = true;
    scan_rays(terrain, window, out, progress, s, samples_);
  }

 private:
  HorizonParams p_;
  FixedDistances samples_;
};

}  // namespace

std::unique_ptr<HorizonEngine> make_sampled_engine(const HorizonParams& params) {
  return std::make_unique<SampledEngine>(params);
}

}  // namespace skyview::detail
