// Hošek–Wilkie against the outputs of the authors' 1.4a C code (reference_values.csv).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sky_test_support.h"
#include "skyview/core/error.h"
#include "skyview/sky/hosek_wilkie.h"
#include "skyview/sky/sky_models.h"

namespace skyview {
namespace {

TEST(HosekWilkie, MatchesReferenceImplementation) {
  SKYVIEW_REQUIRE_SHARED(path, "hosek_wilkie/reference_values.csv");
  int checked = 0;
  double worst = 0.0;
  for (const auto& r : sky_test::read_csv(path)) {
    const std::string model = r.at("model");
    if (model != "spectral" && model != "spectral_sun_plus_sky") continue;
    const double t = std::stod(r.at("turbidity")), albedo = std::stod(r.at("albedo"));
    const double elevation = std::stod(r.at("solar_elevation_deg")) * sky_test::kDeg;
    const double theta = std::stod(r.at("theta_rad")), gamma = std::stod(r.at("gamma_rad"));
    const double wavelength = std::stod(r.at("wavelength_or_channel"));
    const double expected = std::stod(r.at("value"));
    const hosek_wilkie::SpectralSky sky(t, albedo, elevation);
    const double got =
        model == "spectral" ? sky.sky_radiance(theta, gamma, wavelength) : sky.solar_radiance(theta, gamma, wavelength);
    const double rel = std::abs(got - expected) / std::max(std::abs(expected), 1e-300);
    worst = std::max(worst, rel);
    EXPECT_NEAR(got, expected, 1e-10 * std::abs(expected) + 1e-300)
        << model << " T=" << t << " a=" << albedo << " elev=" << elevation << " theta=" << theta << " gamma=" << gamma
        << " nm=" << wavelength;
    ++checked;
  }
  EXPECT_EQ(checked, 2520 + 378);
  RecordProperty("worst_relative_error", std::to_string(worst));
}

TEST(HosekWilkie, BroadbandIsTheTrapezoidOfTheBands) {
  const auto model = make_hosek_wilkie_sky(3.0, 0.2);
  SkyConditions c;
  c.sun_zenith = 40 * sky_test::kDeg;
  const auto sky = model->at(c);
  const hosek_wilkie::SpectralSky spectral(3.0, 0.2, 50 * sky_test::kDeg);
  double expected = 0.0;
  for (int b = 0; b < 11; ++b) expected += (b == 0 || b == 10 ? 20.0 : 40.0) * spectral.band_radiance(b, 0.7, 0.9);
  EXPECT_NEAR(sky->radiance(0.7, 0.9), expected, 1e-12 * expected);
  // A clear noon-ish sun: DNI over 320-720 nm is a few hundred W/m² (≈40 % of the broadband beam).
  EXPECT_GT(sky->direct_normal(), 250.0);
  EXPECT_LT(sky->direct_normal(), 550.0);
}

// The published fit dips below zero at the horizon for a hazy sky over dark ground and a low sun;
// the model holds radiance at zero there, point-wise and tabulated alike.
TEST(HosekWilkie, HazyLowSunSkyHasNoNegativeRadiance) {
  const auto model = make_hosek_wilkie_sky(10.0, 0.0);
  std::vector<double> thetas, gammas;
  for (int i = 0; i <= 180; ++i) thetas.push_back(i * 0.5 * sky_test::kDeg);
  for (int j = 0; j <= 180; ++j) gammas.push_back(j * sky_test::kDeg);
  std::vector<float> table(thetas.size() * gammas.size());
  std::size_t negative = 0;
  for (const double elevation : {1.0, 2.0, 4.0, 8.0}) {
    SkyConditions c;
    c.sun_zenith = (90.0 - elevation) * sky_test::kDeg;
    const auto sky = model->at(c);
    sky->tabulate(thetas, gammas, table.data());
    for (const float v : table) negative += v < 0.0f;
    for (const double th : thetas) {
      for (const double ga : gammas) negative += sky->radiance(th, ga) < 0.0;
    }
  }
  EXPECT_EQ(negative, 0u);
}

TEST(HosekWilkie, RejectsOutOfRangeParameters) {
  EXPECT_THROW(make_hosek_wilkie_sky(0.5, 0.2), Error);
  EXPECT_THROW(make_hosek_wilkie_sky(3, 1.5), Error);
}

}  // namespace
}  // namespace skyview
