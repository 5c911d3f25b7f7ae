// Perez 1993 all-weather sky driven by measured irradiance: the distribution from Table 1,
// normalised each hour so that its horizontal integral equals the measured diffuse horizontal
// irradiance; the sun carries the measured direct normal irradiance.
#include "skyview/sky/perez_all_weather.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "measured_instant.h"
#include "skyview/core/error.h"
#include "skyview/sky/sky_models.h"

namespace skyview::perez {
namespace {

// Perez et al. 1993, Table 1 (via Radiance gendaymtx.c, checked against gendaylit.c): per bin,
// a1..a4, b1..b4, c1..c4, d1..d4, e1..e4.
constexpr double kCoefficients[8][20] = {
    {1.3525, -0.2576, -0.2690, -1.4366, -0.7670, 0.0007, 1.2734, -0.1233, 2.8000,  0.6004,
     1.2375, 1.0000,  1.8734,  0.6297,  0.9738,  0.2809, 0.0356, -0.1246, -0.5718, 0.9938},
    {-1.2219, -0.7730, 1.4148,  1.1016,  -0.2054, 0.0367, -3.9128, 0.9156, 6.9750,  0.1774,
     6.4477,  -0.1239, -1.5798, -0.5081, -1.7812, 0.1080, 0.2624,  0.0672, -0.2190, -0.4285},
    {-1.1000,  -0.2515, 0.8952,  0.0156, 0.2782, -0.1812, -4.5000, 1.1766, 24.7219, -13.0812,
     -37.7000, 34.8438, -5.0000, 1.5218, 3.9229, -2.6204, -0.0156, 0.1597, 0.4199,  -0.5562},
    {-0.5484,  -0.6654, -0.2672, 0.7117, 0.7234, -0.6219, -5.6812, 2.6297,  33.3389, -18.3000,
     -62.2500, 52.0781, -3.5000, 0.0016, 1.1477, 0.1062,  0.4659,  -0.3296, -0.0876, -0.0329},
    {-0.6000,  -0.3566, -2.5000, 2.3250,  0.2937, 0.0496, -5.6812, 1.8415, 21.0000, -4.7656,
     -21.5906, 7.2492,  -3.5000, -0.1554, 1.4062, 0.3988, 0.0032,  0.0766, -0.0656, -0.1294},
    {-1.0156, -0.3670, 1.0078,  1.4051,  0.2875,  -0.5328, -3.8500, 3.3750, 14.0000, -0.9999,
     -7.1406, 7.5469,  -3.4000, -0.1078, -1.0750, 1.5702,  -0.0672, 0.4016, 0.3017,  -0.4844},
    {-1.0000, 0.0211,  0.5025,  -0.5119, -0.3000, 0.1922, 0.7023, -1.6317, 19.0000, -5.0000,
     1.2438,  -1.9094, -4.0000, 0.0250,  0.3844,  0.2656, 1.0468, -0.3788, -2.4517, 1.4656},
    {-1.0500,  0.0289,  0.4260,  0.3590, -0.3250, 0.1156, 0.7781, 0.0025,  31.0625, -14.5000,
     -46.1148, 55.3750, -7.2312, 0.4050, 13.3500, 0.6234, 1.5000, -0.6426, 1.8564,  0.5636}};

constexpr double kBinUpper[7] = {1.065, 1.230, 1.500, 1.950, 2.800, 4.500, 6.200};

constexpr double kMinCosZeta = 0.0871557427476582;  // sin 5°

}  // namespace

double clearness(double dh, double dn, double z) {
  if (dh <= 0.0) return 11.9;
  const double kz3 = 1.041 * z * z * z;
  return ((dh + dn) / dh + kz3) / (1.0 + kz3);
}

double brightness(double dh, double z, double i0) { return dh * relative_air_mass(z) / i0; }

Parameters parameters(double eps, double delta, double z) {
  eps = std::clamp(eps, 1.0, 11.9);
  delta = std::max(delta, 0.01);
  if (eps > 1.065 && eps < 2.8) delta = std::max(delta, 0.2);
  int bin = 0;
  while (bin < 7 && eps >= kBinUpper[bin]) ++bin;
  const double* k = kCoefficients[bin];
  auto linear = [&](int i) { return k[i] + k[i + 1] * z + delta * (k[i + 2] + k[i + 3] * z); };
  Parameters p{linear(0), linear(4), linear(8), linear(12), linear(16), bin + 1};
  if (bin == 0) {
    p.c = std::exp(std::pow(delta * (k[8] + k[9] * z), k[10])) - k[11];
    p.d = -std::exp(delta * (k[12] + k[13] * z)) + k[14] + delta * k[15];
  }
  return p;
}

double gradation(const Parameters& p, double zeta) {
  const double cos_zeta = std::max(std::cos(zeta), kMinCosZeta);
  return std::max(0.0, 1.0 + p.a * std::exp(p.b / cos_zeta));
}

double indicatrix(const Parameters& p, double gamma) {
  const double cos_gamma = std::cos(gamma);
  return std::max(0.0, 1.0 + p.c * std::exp(p.d * gamma) + p.e * cos_gamma * cos_gamma);
}

double relative_radiance(const Parameters& p, double zeta, double gamma) {
  return gradation(p, zeta) * indicatrix(p, gamma);
}

}  // namespace skyview::perez

namespace skyview {
namespace {

class PerezAllWeatherSky final : public SkyModel {
 public:
  std::string name() const override { return "perez-epw"; }
  std::unique_ptr<SkyInstant> at(const SkyConditions& c) const override {
    require_measured(c, "Perez all-weather");
    const double dhi = measured_or_zero(c.diffuse_horizontal);
    const bool up = c.sun_zenith < std::numbers::pi / 2;
    // The sun below the horizon leaves no direction for the beam nor a fit for the sky: keep the
    // measured diffuse energy as a uniform sky, drop the (tiny) beam.
    if (!up) return std::make_unique<MeasuredInstant>(c, true, perez::Parameters{}, dhi, 0.0);
    const double dni = measured_or_zero(c.direct_normal);
    const double eps = perez::clearness(dhi, dni, c.sun_zenith);
    const double delta = perez::brightness(dhi, c.sun_zenith, extraterrestrial_normal_irradiance(c.day_of_year));
    return std::make_unique<MeasuredInstant>(c, false, perez::parameters(eps, delta, c.sun_zenith), dhi, dni);
  }
};

}  // namespace

std::unique_ptr<SkyModel> make_perez_all_weather_sky() { return std::make_unique<PerezAllWeatherSky>(); }

}  // namespace skyview
