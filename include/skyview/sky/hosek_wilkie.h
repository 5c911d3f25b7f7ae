#pragma once
// Hošek & Wilkie spectral sky (ACM TOG 31(4), 2012) with the solar-radiance function of their
// 2013 IEEE CG&A paper, evaluated from the authors' 1.4a coefficient tables (BSD-3-Clause,
// Copyright (c) 2012-2013 Lukas Hosek and Alexander Wilkie; notice in docs/sky.md).
// Angles in radians; radiances in W m⁻² sr⁻¹ nm⁻¹; valid for 320..720 nm.

namespace skyview::hosek_wilkie {

inline constexpr double kSolarRadius = 0.51 * 3.14159265358979323846 / 180.0 / 2.0;

class SpectralSky {
 public:
  // turbidity ∈ [1, 10], albedo ∈ [0, 1], solar elevation ∈ [0, π/2] (clamped).
  SpectralSky(double turbidity, double albedo, double solar_elevation);

  // Sky radiance at a band's wavelength (band 0 = 320 nm ... 10 = 720 nm).
  double band_radiance(int band, double theta, double gamma) const;
  // Sky radiance at any wavelength in 320..720 nm, linear between bands (as the reference code).
  double sky_radiance(double theta, double gamma, double wavelength_nm) const;
  // Direct solar radiance with limb darkening for a view direction at elevation π/2 − θ lying
  // `gamma` from the sun centre; 0 outside the disc.
  double direct_radiance(double theta, double gamma, double wavelength_nm) const;
  // The reference "solar radiance": direct_radiance + sky_radiance.
  double solar_radiance(double theta, double gamma, double wavelength_nm) const {
    return direct_radiance(theta, gamma, wavelength_nm) + sky_radiance(theta, gamma, wavelength_nm);
  }
  // Direct solar radiance at a band (no limb darkening) for elevation `elevation`.
  double band_solar_radiance(int band, double elevation) const;
  // Limb darkening of a band for μ = cos of the position on the disc.
  static double limb_darkening(int band, double mu);
  // ∫ over the disc of limb darkening dΩ / (π r²) for a band: Σ d_i · 2/(i+2).
  static double mean_limb_darkening(int band);

  // Per band: the nine distribution parameters in stored order A B C D E F G I H, and scale L.
  const double* parameters(int band) const { return config_[band]; }
  double scale(int band) const { return scale_[band]; }

 private:
  double turbidity_;
  double config_[11][9];
  double scale_[11];
};

}  // namespace skyview::hosek_wilkie
