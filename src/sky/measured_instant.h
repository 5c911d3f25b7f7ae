#pragma once
// The sky of one instant built from measured irradiance: a diffuse part scaled so its horizontal
// integral equals the measured DHI (uniform, or shaped by the Perez 1993 distribution) and a sun
// carrying the measured DNI. Shared by the Perez all-weather and isotropic skies.
#include <memory>

#include "skyview/sky/perez_all_weather.h"
#include "skyview/sky/sky_model.h"

namespace skyview {

class MeasuredInstant final : public SkyInstant {
 public:
  // uniform: ignore `shape` and spread `dhi` evenly (radiance dhi / π).
  MeasuredInstant(const SkyConditions& c, bool uniform, const perez::Parameters& shape, double dhi, double dni);
  double radiance(double theta, double gamma) const override;
  void tabulate(std::span<const double> thetas, std::span<const double> gammas, float* out) const override;
  double direct_normal() const override { return dni_; }
  bool has_diffuse() const override { return scale_ > 0.0; }

 private:
  bool uniform_;
  perez::Parameters p_;
  double dni_;
  double scale_ = 0.0;
};

// A measured irradiance, with missing (NaN) or negative values read as 0.
double measured_or_zero(double v);

// Throws skyview::Error naming `model` unless DHI and DNI are present.
void require_measured(const SkyConditions& c, const char* model);

}  // namespace skyview
