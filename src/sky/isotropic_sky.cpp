// The isotropic sky: the baseline users compare anisotropic skies with. It spreads the diffuse
// horizontal irradiance of another model (or of measured data) evenly over the hemisphere.
#include <cmath>
#include <numbers>

#include "measured_instant.h"
#include "skyview/sky/sky_models.h"

namespace skyview {
namespace {

class IsotropicSky final : public SkyModel {
 public:
  explicit IsotropicSky(std::shared_ptr<const SkyModel> energy) : energy_(std::move(energy)) {}
  std::string name() const override { return "isotropic"; }
  std::unique_ptr<SkyInstant> at(const SkyConditions& c) const override {
    if (energy_) {
      const auto source = energy_->at(c);
      // 32 zenith steps: the analytic skies are smooth enough for 0.1 % here and it keeps a year fast.
      return std::make_unique<MeasuredInstant>(c, true, perez::Parameters{}, source->diffuse_horizontal(32),
                                               source->direct_normal());
    }
    require_measured(c, "isotropic");
    const double dni = c.sun_zenith < std::numbers::pi / 2 ? measured_or_zero(c.direct_normal) : 0.0;
    return std::make_unique<MeasuredInstant>(c, true, perez::Parameters{}, measured_or_zero(c.diffuse_horizontal), dni);
  }

 private:
  std::shared_ptr<const SkyModel> energy_;
};

}  // namespace

std::unique_ptr<SkyModel> make_isotropic_sky(std::shared_ptr<const SkyModel> energy) {
  return std::make_unique<IsotropicSky>(std::move(energy));
}

}  // namespace skyview
