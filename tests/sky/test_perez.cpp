// Perez 1993 all-weather sky: its coefficients against the published table (shared CSV), and a
// measured sky that stays non-negative and keeps its measured diffuse irradiance where the fitted
// distribution turns negative (overcast, low sun).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "sky_test_support.h"
#include "skyview/sky/perez_all_weather.h"
#include "skyview/sky/sky_models.h"

namespace skyview {
namespace {

using sky_test::kDeg;

// Each bin's parameters at two sun zeniths and two brightnesses give back the table's four
// coefficients per parameter (x = x1 + x2 z + Δ (x3 + x4 z)); bin 1's c and d follow their own forms.
TEST(Perez, ParametersFollowThePublishedTable) {
  SKYVIEW_REQUIRE_SHARED(path, "sky_coefficients/perez1993_allweather.csv");
  const auto rows = sky_test::read_csv(path);
  ASSERT_EQ(rows.size(), 8u);
  for (const auto& r : rows) {
    const int bin = std::stoi(r.at("bin"));
    const double eps = bin == 8 ? 7.0 : 0.5 * (std::stod(r.at("eps_low")) + std::stod(r.at("eps_high")));
    auto k = [&](const char* name, int i) { return std::stod(r.at(name + std::to_string(i))); };
    for (const double z : {0.3, 1.2}) {
      for (const double delta : {0.25, 0.4}) {  // at or above every guard's floor
        const perez::Parameters p = perez::parameters(eps, delta, z);
        EXPECT_EQ(p.bin, bin);
        auto expected = [&](const char* name) {
          return k(name, 1) + k(name, 2) * z + delta * (k(name, 3) + k(name, 4) * z);
        };
        EXPECT_NEAR(p.a, expected("a"), 1e-12) << "bin " << bin;
        EXPECT_NEAR(p.b, expected("b"), 1e-12) << "bin " << bin;
        EXPECT_NEAR(p.e, expected("e"), 1e-12) << "bin " << bin;
        if (bin == 1) {
          EXPECT_NEAR(p.c, std::exp(std::pow(delta * (k("c", 1) + k("c", 2) * z), k("c", 3))) - k("c", 4), 1e-12);
          EXPECT_NEAR(p.d, -std::exp(delta * (k("d", 1) + k("d", 2) * z)) + k("d", 3) + delta * k("d", 4), 1e-12);
        } else {
          EXPECT_NEAR(p.c, expected("c"), 1e-12) << "bin " << bin;
          EXPECT_NEAR(p.d, expected("d"), 1e-12) << "bin " << bin;
        }
      }
    }
  }
}

// Overcast with the sun 1.25° up (Mannheim, 14 January 2005, 09 h: DHI 47 W/m², no beam): the air
// mass of 26 makes the brightness Δ about 0.9, where bin 1's fitted gradation is negative over the
// lower sky. Until Dec 3 the relative integral came out negative and the hour's DHI was dropped
// (has_diffuse false), or, at DHI 38 (a small positive integral), the sky held radiances of
// -3800 Wh m⁻² sr⁻¹ that sent an east wall's diffuse irradiation below zero.
TEST(Perez, OvercastLowSunKeepsItsMeasuredDiffuseAndNoNegativeSky) {
  const auto model = make_perez_all_weather_sky();
  std::size_t negative = 0;
  for (const double elevation : {1.25, 2.0, 3.0, 4.0, 6.0}) {
    for (double dhi = 20.0; dhi <= 120.0; dhi += 10.0) {
      SkyConditions c;
      c.sun_zenith = (90.0 - elevation) * kDeg;
      c.sun_azimuth = 130.0 * kDeg;
      c.day_of_year = 14;
      c.diffuse_horizontal = dhi;
      c.direct_normal = 0.0;
      c.global_horizontal = dhi;
      const auto sky = model->at(c);
      EXPECT_TRUE(sky->has_diffuse()) << "DHI " << dhi << ", sun " << elevation << " deg up";
      EXPECT_NEAR(sky->diffuse_horizontal(90), dhi, 0.01 * dhi);
      std::vector<double> thetas, gammas;
      for (int i = 0; i <= 90; ++i) thetas.push_back(i * kDeg);
      for (int j = 0; j <= 180; ++j) gammas.push_back(j * kDeg);
      std::vector<float> table(thetas.size() * gammas.size());
      sky->tabulate(thetas, gammas, table.data());
      for (std::size_t i = 0; i < table.size(); ++i) negative += table[i] < 0.0f;
      // The tabulated sky is the point-wise one.
      for (const std::size_t i : {0u, 45u, 88u, 90u}) {
        for (const std::size_t j : {0u, 60u, 180u}) {
          EXPECT_NEAR(table[i * gammas.size() + j], sky->radiance(thetas[i], gammas[j]),
                      1e-5 * (1.0 + std::abs(sky->radiance(thetas[i], gammas[j]))));
        }
      }
    }
  }
  EXPECT_EQ(negative, 0u) << "tabulated radiances below zero";
}

}  // namespace
}  // namespace skyview
