// Hošek–Wilkie 2012 sky and 2013 solar-radiance function from the generated 1.4a tables, and
// the broadband SkyModel that integrates the eleven bands (320..720 nm) by the trapezoid rule.
#include "skyview/sky/hosek_wilkie.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "hosek_wilkie_tables.h"
#include "skyview/core/error.h"
#include "skyview/sky/sky_models.h"

namespace skyview::hosek_wilkie {
namespace {

// Quintic Bézier over six control points spaced `stride` apart.
double bezier(const double* c, int stride, double x) {
  const double y = 1.0 - x;
  return y * y * y * y * y * c[0] + 5 * y * y * y * y * x * c[stride] + 10 * y * y * y * x * x * c[2 * stride] +
         10 * y * y * x * x * x * c[3 * stride] + 5 * y * x * x * x * x * c[4 * stride] +
         x * x * x * x * x * c[5 * stride];
}

// Blend over albedo and turbidity as the reference code does; `cook(albedo_index, turbidity_index)`
// returns the Bézier value for one stored pair.
template <class Cook>
double blend(double turbidity, double albedo, Cook cook) {
  const int t0 = static_cast<int>(turbidity);
  const double f = turbidity - t0;
  double v = (1 - albedo) * (1 - f) * cook(0, t0 - 1) + albedo * (1 - f) * cook(1, t0 - 1);
  if (t0 < 10) v += (1 - albedo) * f * cook(0, t0) + albedo * f * cook(1, t0);
  return v;
}

double distribution(const double* p, double theta, double gamma) {
  const double cos_gamma = std::cos(gamma);
  const double cos_theta = std::cos(theta);
  const double exp_m = std::exp(p[4] * gamma);
  const double ray_m = cos_gamma * cos_gamma;
  const double mie_m = (1.0 + ray_m) / std::pow(1.0 + p[8] * p[8] - 2.0 * p[8] * cos_gamma, 1.5);
  const double zenith = std::sqrt(std::max(cos_theta, 0.0));
  return (1.0 + p[0] * std::exp(p[1] / (cos_theta + 0.01))) *
         (p[2] + p[3] * exp_m + p[5] * ray_m + p[6] * mie_m + p[7] * zenith);
}

double segment_value(int band, int turbidity_index, double elevation) {
  constexpr int kPieces = 45;
  int pos = static_cast<int>(std::pow(2.0 * elevation / std::numbers::pi, 1.0 / 3.0) * kPieces);
  pos = std::clamp(pos, 0, kPieces - 1);
  const double break_x = std::pow(static_cast<double>(pos) / kPieces, 3.0) * (std::numbers::pi / 2);
  const double* k = kSolarSegments + ((band * 10 + turbidity_index) * kPieces + pos) * 4;  // k3 k2 k1 k0
  const double u = elevation - break_x;
  return k[3] + u * (k[2] + u * (k[1] + u * k[0]));
}

}  // namespace

SpectralSky::SpectralSky(double turbidity, double albedo, double solar_elevation) : turbidity_(turbidity) {
  const double x = std::cbrt(std::clamp(solar_elevation, 0.0, std::numbers::pi / 2) / (std::numbers::pi / 2));
  for (int b = 0; b < kBands; ++b) {
    for (int p = 0; p < 9; ++p) {
      config_[b][p] = blend(turbidity, albedo, [&](int a, int t) {
        return bezier(kSkyParams + (((b * 2 + a) * 10 + t) * 6) * 9 + p, 9, x);
      });
    }
    scale_[b] =
        blend(turbidity, albedo, [&](int a, int t) { return bezier(kSkyRadiance + ((b * 2 + a) * 10 + t) * 6, 1, x); });
  }
}

double SpectralSky::band_radiance(int band, double theta, double gamma) const {
  return distribution(config_[band], theta, gamma) * scale_[band];
}

double SpectralSky::sky_radiance(double theta, double gamma, double wavelength_nm) const {
  const double pos = (wavelength_nm - kFirstBandNm) / kBandStepNm;
  if (pos < 0.0 || pos >= kBands) return 0.0;
  const int low = static_cast<int>(pos);
  const double frac = pos - low;
  const double low_value = band_radiance(low, theta, gamma);
  if (frac < 1e-6) return low_value;
  double result = (1.0 - frac) * low_value;
  if (low + 1 < kBands) result += frac * band_radiance(low + 1, theta, gamma);
  return result;
}

double SpectralSky::band_solar_radiance(int band, double elevation) const {
  int t0 = static_cast<int>(turbidity_) - 1;
  double f = turbidity_ - (t0 + 1);
  if (t0 == 9) {
    t0 = 8;
    f = 1.0;
  }
  return (1 - f) * segment_value(band, t0, elevation) + f * segment_value(band, t0 + 1, elevation);
}

double SpectralSky::limb_darkening(int band, double mu) {
  const double* d = kLimbDarkening + band * 6;
  return d[0] + mu * (d[1] + mu * (d[2] + mu * (d[3] + mu * (d[4] + mu * d[5]))));
}

double SpectralSky::mean_limb_darkening(int band) {
  const double* d = kLimbDarkening + band * 6;
  double sum = 0.0;
  for (int i = 0; i < 6; ++i) sum += d[i] * 2.0 / (i + 2.0);
  return sum;
}

double SpectralSky::direct_radiance(double theta, double gamma, double wavelength_nm) const {
  const double sin_r = std::sin(kSolarRadius);
  const double sin_g = std::sin(gamma);
  const double sc2 = 1.0 - sin_g * sin_g / (sin_r * sin_r);
  if (gamma > kSolarRadius || sc2 < 0.0) return 0.0;
  const double mu = std::sqrt(sc2);
  int w0 = static_cast<int>((wavelength_nm - kFirstBandNm) / kBandStepNm);
  double g = std::fmod(wavelength_nm, kBandStepNm) / kBandStepNm;
  if (w0 == kBands - 1) {
    w0 = kBands - 2;
    g = 1.0;
  }
  if (w0 < 0 || w0 > kBands - 2) return 0.0;
  const double elevation = std::numbers::pi / 2 - theta;
  const double direct = (1 - g) * band_solar_radiance(w0, elevation) + g * band_solar_radiance(w0 + 1, elevation);
  const double darkening = (1 - g) * limb_darkening(w0, mu) + g * limb_darkening(w0 + 1, mu);
  return direct * darkening;
}

}  // namespace skyview::hosek_wilkie

namespace skyview {
namespace {

using hosek_wilkie::kBands;
using hosek_wilkie::SpectralSky;

// Trapezoid weights (nm) of the eleven bands over 320..720 nm.
double band_weight(int b) { return (b == 0 || b == kBands - 1) ? 20.0 : 40.0; }

class HosekWilkieInstant final : public SkyInstant {
 public:
  HosekWilkieInstant(double turbidity, double albedo, const SkyConditions& c)
      : SkyInstant(c.sun_zenith, c.sun_azimuth),
        up_(c.sun_zenith < std::numbers::pi / 2),
        sky_(turbidity, albedo, std::numbers::pi / 2 - c.sun_zenith) {
    if (!up_) return;
    const double elevation = std::numbers::pi / 2 - c.sun_zenith;
    const double disc = 2.0 * std::numbers::pi * (1.0 - std::cos(hosek_wilkie::kSolarRadius));
    for (int b = 0; b < kBands; ++b) {
      dni_ += band_weight(b) * sky_.band_solar_radiance(b, elevation) * SpectralSky::mean_limb_darkening(b) * disc;
    }
  }

  double radiance(double theta, double gamma) const override {
    if (!up_ || theta > std::numbers::pi / 2) return 0.0;
    double sum = 0.0;
    for (int b = 0; b < kBands; ++b) sum += band_weight(b) * sky_.band_radiance(b, theta, gamma);
    // The published fit dips just below zero at the horizon for hazy skies over dark ground and a low
    // sun (-0.05 Wh m^-2 sr^-1 at T = 10, albedo 0); radiance cannot.
    return std::max(sum, 0.0);
  }

  // Per band the distribution is g(θ)·(f(γ) + I·√cos θ), so the broadband table is
  // S(θ) + Σ_b G_b(θ)·F_b(γ): eleven small vectors per step, then one cache-resident row at a time.
  void tabulate(std::span<const double> thetas, std::span<const double> gammas, float* out) const override {
    const std::size_t nt = thetas.size(), ng = gammas.size();
    if (!up_) {
      std::fill(out, out + nt * ng, 0.0f);
      return;
    }
    std::vector<float> f(kBands * ng), g(kBands);
    for (int b = 0; b < kBands; ++b) {
      const double* p = sky_.parameters(b);
      for (std::size_t j = 0; j < ng; ++j) {
        const double cg = std::cos(gammas[j]);
        f[b * ng + j] = static_cast<float>(p[2] + p[3] * std::exp(p[4] * gammas[j]) + p[5] * cg * cg +
                                           p[6] * (1.0 + cg * cg) / std::pow(1.0 + p[8] * p[8] - 2.0 * p[8] * cg, 1.5));
      }
    }
    for (std::size_t i = 0; i < nt; ++i) {
      const double ct = std::cos(thetas[i]);
      double along_theta = 0.0;
      for (int b = 0; b < kBands; ++b) {
        const double* p = sky_.parameters(b);
        const double gb = band_weight(b) * sky_.scale(b) * (1.0 + p[0] * std::exp(p[1] / (ct + 0.01)));
        g[b] = static_cast<float>(gb);
        along_theta += gb * p[7] * std::sqrt(std::max(ct, 0.0));
      }
      float* row = out + i * ng;
      std::fill(row, row + ng, static_cast<float>(along_theta));
      for (int b = 0; b < kBands; ++b) {
        const float* fb = f.data() + b * ng;
        for (std::size_t j = 0; j < ng; ++j) row[j] += g[b] * fb[j];
      }
      for (std::size_t j = 0; j < ng; ++j) row[j] = std::max(row[j], 0.0f);  // as radiance()
    }
  }

  double direct_normal() const override { return dni_; }
  bool has_diffuse() const override { return up_; }

  double sun_radiance(double gamma) const override {
    if (!up_ || gamma > hosek_wilkie::kSolarRadius) return 0.0;
    const double s = std::sin(gamma) / std::sin(hosek_wilkie::kSolarRadius);
    const double mu = std::sqrt(std::max(0.0, 1.0 - s * s));
    double sum = 0.0;
    for (int b = 0; b < kBands; ++b) {
      sum += band_weight(b) * sky_.band_solar_radiance(b, std::numbers::pi / 2 - sun_zenith()) *
             SpectralSky::limb_darkening(b, mu);
    }
    return sum;
  }

  double sun_angular_radius() const override { return hosek_wilkie::kSolarRadius; }

 private:
  bool up_;
  SpectralSky sky_;
  double dni_ = 0.0;
};

class HosekWilkieSky final : public SkyModel {
 public:
  HosekWilkieSky(double turbidity, double albedo) : turbidity_(turbidity), albedo_(albedo) {}
  std::string name() const override { return "hosek"; }
  std::unique_ptr<SkyInstant> at(const SkyConditions& c) const override {
    return std::make_unique<HosekWilkieInstant>(turbidity_, albedo_, c);
  }

 private:
  double turbidity_, albedo_;
};

}  // namespace

std::unique_ptr<SkyModel> make_hosek_wilkie_sky(double turbidity, double albedo) {
  if (!(turbidity >= 1.0 && turbidity <= 10.0)) {
    throw Error("Hosek-Wilkie sky: turbidity must be within 1 .. 10 (got " + std::to_string(turbidity) + ")");
  }
  if (!(albedo >= 0.0 && albedo <= 1.0)) {
    throw Error("Hosek-Wilkie sky: albedo must be within 0 .. 1 (got " + std::to_string(albedo) + ")");
  }
  return std::make_unique<HosekWilkieSky>(turbidity, albedo);
}

}  // namespace skyview
