// Preetham 1999 sky (Appendix A.2 of the paper, the "paper" variant of the coefficients in
// ../shared/data/sky_coefficients/preetham1999_*.csv) and its broadband SkyModel.
#include "skyview/sky/preetham.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "skyview/core/error.h"
#include "skyview/core/number_text.h"
#include "skyview/sky/sky_models.h"

namespace skyview::preetham {
namespace {

// {slope per T, intercept} for A..E, per component (Preetham et al. 1999, Appendix A.2).
constexpr double kDistribution[3][5][2] = {
    {{0.1787, -1.4630}, {-0.3554, 0.4275}, {-0.0227, 5.3251}, {0.1206, -2.5771}, {-0.0670, 0.3703}},     // Y
    {{-0.0193, -0.2592}, {-0.0665, 0.0008}, {-0.0004, 0.2125}, {-0.0641, -0.8989}, {-0.0033, 0.0452}},   // x
    {{-0.0167, -0.2608}, {-0.0950, 0.0092}, {-0.0079, 0.2102}, {-0.0441, -1.6537}, {-0.0109, 0.0529}}};  // y

// Zenith chromaticity matrices: rows T², T, 1; columns Z³, Z², Z, 1.
constexpr double kZenithX[3][4] = {{0.00166, -0.00375, 0.00209, 0.00000},
                                   {-0.02903, 0.06377, -0.03202, 0.00394},
                                   {0.11693, -0.21196, 0.06052, 0.25886}};
constexpr double kZenithY[3][4] = {{0.00275, -0.00610, 0.00317, 0.00000},
                                   {-0.04214, 0.08970, -0.04153, 0.00516},
                                   {0.15346, -0.26756, 0.06670, 0.26688}};

double chromaticity(const double (&m)[3][4], double t, double z) {
  const double tv[3] = {t * t, t, 1.0};
  const double zv[4] = {z * z * z, z * z, z, 1.0};
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) sum += tv[i] * m[i][j] * zv[j];
  }
  return sum;
}

// The fit is for a sun above the horizon; the paper gives no guard for θ → 90°, so clamp.
constexpr double kMinCos = 0.01;

}  // namespace

PerezCoefficients coefficients(Component c, double t) {
  const auto& k = kDistribution[static_cast<int>(c)];
  return {k[0][0] * t + k[0][1], k[1][0] * t + k[1][1], k[2][0] * t + k[2][1], k[3][0] * t + k[3][1],
          k[4][0] * t + k[4][1]};
}

double perez(const PerezCoefficients& k, double theta, double gamma) {
  const double cos_theta = std::max(std::cos(theta), kMinCos);
  const double cos_gamma = std::cos(gamma);
  return (1.0 + k.A * std::exp(k.B / cos_theta)) * (1.0 + k.C * std::exp(k.D * gamma) + k.E * cos_gamma * cos_gamma);
}

Yxy zenith(double t, double sun_zenith) {
  const double chi = (4.0 / 9.0 - t / 120.0) * (std::numbers::pi - 2.0 * sun_zenith);
  const double y_kcd = (4.0453 * t - 4.9710) * std::tan(chi) - 0.2155 * t + 2.4192;
  return {1000.0 * y_kcd, chromaticity(kZenithX, t, sun_zenith), chromaticity(kZenithY, t, sun_zenith)};
}

Yxy sky(double t, double sun_zenith, double theta, double gamma) {
  const Yxy z = zenith(t, sun_zenith);
  auto component = [&](Component c, double zv) {
    const PerezCoefficients k = coefficients(c, t);
    return zv * perez(k, theta, gamma) / perez(k, 0.0, sun_zenith);
  };
  return {component(Component::Y, z.Y), component(Component::x, z.x), component(Component::y, z.y)};
}

XYZ to_xyz(const Yxy& c) {
  if (c.y <= 0.0) return {};
  return {c.x / c.y * c.Y, c.Y, (1.0 - c.x - c.y) / c.y * c.Y};
}

LinearRgb to_linear_srgb(const XYZ& c) {
  return {3.2404542 * c.X - 1.5371385 * c.Y - 0.4985314 * c.Z, -0.9692660 * c.X + 1.8760108 * c.Y + 0.0415560 * c.Z,
          0.0556434 * c.X - 0.2040259 * c.Y + 1.0572252 * c.Z};
}

}  // namespace skyview::preetham

namespace skyview {
namespace {

// Preetham's sun (Appendix A.3 transmittances): Rayleigh and Ångström aerosol extinction of a
// 5778 K blackbody scaled to the extraterrestrial irradiance. Ozone, mixed gases and water vapour
// are left out (their absorption tables are not in the shared data), so DNI is an upper estimate.
class PreethamSun {
 public:
  explicit PreethamSun(double turbidity) : beta_(0.04608 * turbidity - 0.04586) {
    constexpr double h = 6.62607015e-34, c = 2.99792458e8, k = 1.380649e-23, t = 5778.0;
    double total = 0.0;
    for (double nm = 250.0; nm <= 4000.0; nm += kStepNm) {
      const double l = nm * 1e-9;
      const double planck = 1.0 / (std::pow(l, 5) * (std::exp(h * c / (l * k * t)) - 1.0));
      wavelengths_um_.push_back(nm / 1000.0);
      spectrum_.push_back(planck);
      total += planck * kStepNm;
    }
    for (double& s : spectrum_) s *= kStepNm / total;  // fractions of the total, per step
  }

  double direct_normal(double sun_zenith, int day_of_year) const {
    if (sun_zenith >= std::numbers::pi / 2) return 0.0;
    const double z_deg = sun_zenith * 180.0 / std::numbers::pi;
    const double m = 1.0 / (std::cos(sun_zenith) + 0.15 * std::pow(93.885 - z_deg, -1.253));
    double sum = 0.0;
    for (std::size_t i = 0; i < spectrum_.size(); ++i) {
      const double l = wavelengths_um_[i];
      const double rayleigh = std::exp(-0.008735 * std::pow(l, -4.08) * m);
      const double aerosol = std::exp(-beta_ * std::pow(l, -1.3) * m);
      sum += spectrum_[i] * rayleigh * aerosol;
    }
    return sum * extraterrestrial_normal_irradiance(day_of_year);
  }

 private:
  static constexpr double kStepNm = 10.0;
  double beta_;
  std::vector<double> wavelengths_um_, spectrum_;
};

class PreethamInstant final : public SkyInstant {
 public:
  PreethamInstant(double turbidity, double efficacy, const PreethamSun& sun, const SkyConditions& c)
      : SkyInstant(c.sun_zenith, c.sun_azimuth), k_(preetham::coefficients(preetham::Component::Y, turbidity)) {
    up_ = c.sun_zenith < std::numbers::pi / 2;
    if (!up_) return;
    const double zenith_luminance = preetham::zenith(turbidity, c.sun_zenith).Y;
    scale_ = zenith_luminance / preetham::perez(k_, 0.0, c.sun_zenith) / efficacy;
    dni_ = sun.direct_normal(c.sun_zenith, c.day_of_year);
  }

  double radiance(double theta, double gamma) const override {
    if (!up_ || theta > std::numbers::pi / 2) return 0.0;
    return scale_ * preetham::perez(k_, theta, gamma);
  }

  void tabulate(std::span<const double> thetas, std::span<const double> gammas, float* out) const override {
    std::vector<double> along_gamma(gammas.size());
    for (std::size_t j = 0; j < gammas.size(); ++j) {
      const double cg = std::cos(gammas[j]);
      along_gamma[j] = 1.0 + k_.C * std::exp(k_.D * gammas[j]) + k_.E * cg * cg;
    }
    for (std::size_t i = 0; i < thetas.size(); ++i) {
      const double along_theta =
          up_ ? scale_ * (1.0 + k_.A * std::exp(k_.B / std::max(std::cos(thetas[i]), 0.01))) : 0.0;
      float* row = out + i * gammas.size();
      for (std::size_t j = 0; j < gammas.size(); ++j) row[j] = static_cast<float>(along_theta * along_gamma[j]);
    }
  }

  double direct_normal() const override { return dni_; }
  bool has_diffuse() const override { return up_; }

 private:
  preetham::PerezCoefficients k_;
  bool up_ = false;
  double scale_ = 0.0, dni_ = 0.0;
};

class PreethamSky final : public SkyModel {
 public:
  PreethamSky(double turbidity, double efficacy) : turbidity_(turbidity), efficacy_(efficacy), sun_(turbidity) {}
  std::string name() const override { return "preetham"; }
  std::unique_ptr<SkyInstant> at(const SkyConditions& c) const override {
    return std::make_unique<PreethamInstant>(turbidity_, efficacy_, sun_, c);
  }

 private:
  double turbidity_, efficacy_;
  PreethamSun sun_;
};

}  // namespace

std::unique_ptr<SkyModel> make_preetham_sky(double turbidity, double luminous_efficacy_lm_per_w) {
  // Below 2, the bottom of the fit, F(0, Z) heads for zero (at T = 1.643) and the diffuse part blows
  // up: the clearest sky would be the brightest (docs/sky.md).
  if (!(turbidity >= 2.0 && turbidity <= 10.0)) {
    throw Error("Preetham sky: turbidity must be within 2 .. 10 (got " + number_text(turbidity) + ")");
  }
  if (!(luminous_efficacy_lm_per_w > 0.0)) throw Error("Preetham sky: luminous efficacy must be positive");
  return std::make_unique<PreethamSky>(turbidity, luminous_efficacy_lm_per_w);
}

}  // namespace skyview
