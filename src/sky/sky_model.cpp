// Shared parts of every sky: the generic tabulation, the uniform sun disc and the
// horizontal-diffuse quadrature used to normalise and check the models.
#include "skyview/sky/sky_model.h"

#include <algorithm>
#include <numbers>
#include <vector>

namespace skyview {

void SkyInstant::tabulate(std::span<const double> thetas, std::span<const double> gammas, float* out) const {
  for (std::size_t i = 0; i < thetas.size(); ++i) {
    for (std::size_t j = 0; j < gammas.size(); ++j) {
      out[i * gammas.size() + j] = static_cast<float>(radiance(thetas[i], gammas[j]));
    }
  }
}

double SkyInstant::sun_radiance(double gamma) const {
  const double r = sun_angular_radius();
  if (gamma > r) return 0.0;
  return direct_normal() / (2.0 * std::numbers::pi * (1.0 - std::cos(r)));
}

double SkyInstant::diffuse_horizontal(int zenith_steps) const {
  const int nz = std::max(zenith_steps, 4);
  const int na = 2 * nz;
  const double dz = std::numbers::pi / 2 / nz;
  const double da = 2 * std::numbers::pi / na;
  // Symmetric about the sun's vertical plane: integrate relative azimuth over [0, π] twice.
  double sum = 0.0;
  for (int i = 0; i < nz; ++i) {
    const double theta = (i + 0.5) * dz;
    // Exact solid angle of the ring times cos θ at its centre; the ring weight ∫cos·sin dθ exactly.
    const double ring = 0.5 * (std::pow(std::sin((i + 1) * dz), 2) - std::pow(std::sin(i * dz), 2));
    double row = 0.0;
    for (int k = 0; k < na / 2; ++k) {
      const double dphi = (k + 0.5) * da;
      const double cos_gamma =
          std::sin(theta) * std::sin(sun_zenith_) * std::cos(dphi) + std::cos(theta) * std::cos(sun_zenith_);
      row += radiance(theta, std::acos(std::clamp(cos_gamma, -1.0, 1.0)));
    }
    sum += 2.0 * row * da * ring;
  }
  return sum;
}

double extraterrestrial_normal_irradiance(int day_of_year) {
  const double b = 2.0 * std::numbers::pi * (day_of_year - 1) / 365.0;
  return kSolarConstant * (1.00011 + 0.034221 * std::cos(b) + 0.00128 * std::sin(b) + 0.000719 * std::cos(2 * b) +
                           0.000077 * std::sin(2 * b));
}

double relative_air_mass(double zenith) {
  const double z_deg = std::min(zenith * 180.0 / std::numbers::pi, 90.0);
  return 1.0 / (std::cos(z_deg * std::numbers::pi / 180.0) + 0.50572 * std::pow(96.07995 - z_deg, -1.6364));
}

double angle_between(double zenith_a, double azimuth_a, double zenith_b, double azimuth_b) {
  const double c = std::sin(zenith_a) * std::sin(zenith_b) * std::cos(azimuth_a - azimuth_b) +
                   std::cos(zenith_a) * std::cos(zenith_b);
  return std::acos(std::clamp(c, -1.0, 1.0));
}

}  // namespace skyview
