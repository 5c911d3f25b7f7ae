#pragma once
// Sky models: the radiance of the sky in any direction and the sun's disc, for one sun position.
// Angles in radians. View directions are given by their zenith angle θ and the angle γ between
// them and the sun centre; every model here is rotationally symmetric about the vertical, so
// these two angles (with the sun's zenith) determine the radiance. Radiances are broadband,
// W m⁻² sr⁻¹ over the spectral range each model covers (docs/sky.md says which).
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <string>

namespace skyview {

// What a sky needs to know about one instant.
struct SkyConditions {
  double sun_zenith = 0.0;   // topocentric, refracted (radians)
  double sun_azimuth = 0.0;  // clockwise from north (radians)
  int day_of_year = 172;     // 1..366, for the extraterrestrial irradiance
  // Measured irradiances for data-driven skies (W/m²); NaN for analytic skies.
  double global_horizontal = std::numeric_limits<double>::quiet_NaN();
  double diffuse_horizontal = std::numeric_limits<double>::quiet_NaN();
  double direct_normal = std::numeric_limits<double>::quiet_NaN();
};

// Mean angular radius of the solar disc (0.53° apparent diameter).
inline constexpr double kSunAngularRadius = 0.2665 * 3.14159265358979323846 / 180.0;

// The sky at one instant.
class SkyInstant {
 public:
  virtual ~SkyInstant() = default;

  // Sky radiance (sun excluded) towards view zenith angle `theta` at angle `gamma` from the sun.
  // Zero below the horizon (theta > π/2).
  virtual double radiance(double theta, double gamma) const = 0;

  // out[i * gammas.size() + j] = radiance(thetas[i], gammas[j]) for all upper-hemisphere thetas.
  // Models override this with their separable form (a function of θ times a function of γ), which
  // makes a year of 512×512 maps affordable.
  virtual void tabulate(std::span<const double> thetas, std::span<const double> gammas, float* out) const;

  // Irradiance of the sun disc on a surface normal to it (W/m²); 0 when the sun is down.
  virtual double direct_normal() const = 0;

  // Radiance of the sun disc at angle `gamma` from its centre (W m⁻² sr⁻¹), 0 outside the disc.
  // Default: a uniform disc carrying direct_normal().
  virtual double sun_radiance(double gamma) const;

  virtual double sun_angular_radius() const { return kSunAngularRadius; }

  // False when the sky is dark (sun down, no measured diffuse light), so integration can skip it.
  virtual bool has_diffuse() const { return true; }

  // ∫ radiance·cos θ dΩ over the upper hemisphere (W/m²), by a fixed midpoint quadrature of
  // `zenith_steps` × 2·`zenith_steps` directions (exact enough for normalising and testing).
  double diffuse_horizontal(int zenith_steps = 90) const;

  // Sun position this instant was built for.
  double sun_zenith() const { return sun_zenith_; }
  double sun_azimuth() const { return sun_azimuth_; }

 protected:
  SkyInstant(double sun_zenith, double sun_azimuth) : sun_zenith_(sun_zenith), sun_azimuth_(sun_azimuth) {}

 private:
  double sun_zenith_, sun_azimuth_;
};

// A sky model builds the sky of each instant.
class SkyModel {
 public:
  virtual ~SkyModel() = default;
  virtual std::string name() const = 0;
  // Throws skyview::Error when the conditions lack what the model needs (e.g. measured data).
  virtual std::unique_ptr<SkyInstant> at(const SkyConditions& conditions) const = 0;
};

// Solar constant (W/m², Kopp & Lean 2011) and its yearly variation with the Earth-Sun distance
// (Spencer 1971 first-harmonic form used by Perez et al.).
inline constexpr double kSolarConstant = 1361.0;
double extraterrestrial_normal_irradiance(int day_of_year);

// Relative optical air mass, Kasten & Young 1989, for a zenith angle in radians (finite at 90°).
double relative_air_mass(double zenith);

// The angle between two directions given by zenith angle and azimuth (radians).
double angle_between(double zenith_a, double azimuth_a, double zenith_b, double azimuth_b);

}  // namespace skyview
