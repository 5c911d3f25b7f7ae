// The exposure map's energy balance and geometry: cosine-weighted integrals against irradiation
// summed step by step, measured-data reproduction, symmetry, and the solstice sun band.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "sky_test_support.h"
#include "skyview/solar/civil_time.h"
#include "skyview/sky/epw.h"
#include "skyview/sky/exposure_map.h"
#include "skyview/sky/exposure_pyramid.h"
#include "skyview/sky/exposure_steps.h"
#include "skyview/sky/sky_models.h"
#include "skyview/solar/time_parse.h"

namespace skyview {
namespace {

using sky_test::kDeg;
constexpr Direction kUp{0, 0, 1};

struct Reference {
  double direct_horizontal = 0, diffuse_horizontal = 0;  // Wh/m²
};

// Irradiation summed over the steps with a quadrature independent of the map's.
Reference step_by_step(const SkyModel& model, const std::vector<ExposureStep>& steps) {
  Reference r;
  for (const auto& s : steps) {
    const auto sky = model.at(s.conditions);
    if (s.conditions.sun_zenith < std::numbers::pi / 2) {
      r.direct_horizontal += sky->direct_normal() * std::cos(s.conditions.sun_zenith) * s.hours;
    }
    if (sky->has_diffuse()) r.diffuse_horizontal += sky->diffuse_horizontal(90) * s.hours;
  }
  return r;
}

std::vector<ExposureStep> days(double lat, double lon, const std::string& from, const std::string& to,
                               double step_s = 1800) {
  Site site;
  site.latitude_deg = lat;
  site.longitude_deg = lon;
  return regular_steps(site, parse_time(from).unix_utc, parse_time(to).unix_utc, step_s);
}

void expect_energy_balance(const SkyModel& model, double lat) {
  const auto steps = days(lat, 10.0, "2024-06-19T00:00Z", "2024-06-21T00:00Z");
  ExposureOptions o;
  o.width = 256;
  o.height = 256;
  const ExposureMap map = integrate_exposure(model, steps, o);
  const Reference ref = step_by_step(model, steps);
  const double direct = map.irradiation(ExposureBand::direct, kUp);
  const double diffuse = map.irradiation(ExposureBand::diffuse, kUp);
  const double global = map.irradiation(ExposureBand::global, kUp);
  const double expected = ref.direct_horizontal + ref.diffuse_horizontal;
  EXPECT_GT(ref.diffuse_horizontal, 0.0);
  EXPECT_NEAR(global, expected, 0.005 * expected) << model.name();
  EXPECT_NEAR(direct, ref.direct_horizontal, 0.001 * ref.direct_horizontal) << model.name();
  EXPECT_NEAR(diffuse, ref.diffuse_horizontal, 0.005 * ref.diffuse_horizontal) << model.name();
  std::printf("[ sky      ] %s: global %.6g Wh/m2, step sum %.6g, relative error %+.4f %%\n", model.name().c_str(),
              global, expected, 100 * (global / expected - 1));
}

TEST(ExposureMap, GlobalHorizontalMatchesStepSumPreetham) { expect_energy_balance(*make_preetham_sky(2.5), 45.0); }
TEST(ExposureMap, GlobalHorizontalMatchesStepSumHosek) {
  expect_energy_balance(*make_hosek_wilkie_sky(2.5, 0.2), 45.0);
}
TEST(ExposureMap, GlobalHorizontalMatchesStepSumIsotropic) {
  expect_energy_balance(*make_isotropic_sky(make_preetham_sky(4.0)), 30.0);
}

TEST(ExposureMap, DirectBandIntegratesToBeamOnEveryOrientation) {
  const auto model = make_hosek_wilkie_sky(3.0, 0.1);
  const auto steps = days(30.0, 0.0, "2024-03-01T00:00Z", "2024-03-03T00:00Z", 900);
  const ExposureMap map = integrate_exposure(*model, steps, {});
  for (const Direction n :
       {Direction{0, 0, 1}, Direction{0, -1, 0}, Direction{1, 0, 0}, Direction{0.5, -0.5, 0.7071}}) {
    double expected = 0;
    for (const auto& s : steps) {
      if (s.conditions.sun_zenith >= std::numbers::pi / 2) continue;
      const double z = s.conditions.sun_zenith, a = s.conditions.sun_azimuth;
      const double c = n[0] * std::sin(z) * std::sin(a) + n[1] * std::sin(z) * std::cos(a) + n[2] * std::cos(z);
      if (c > 0) expected += model->at(s.conditions)->direct_normal() * c * s.hours;
    }
    EXPECT_NEAR(map.irradiation(ExposureBand::direct, n), expected, 0.002 * expected + 1e-6);
  }
}

TEST(ExposureMap, EquatorEquinoxIsSymmetricEastWest) {
  const auto steps = days(0.0, 0.0, "2024-03-20T00:00Z", "2024-03-21T00:00Z", 600);
  ExposureOptions o;
  o.width = 256;
  o.height = 128;
  const ExposureMap map = integrate_exposure(*make_preetham_sky(2.5), steps, o);
  for (ExposureBand b : {ExposureBand::direct, ExposureBand::diffuse}) {
    const double east = map.irradiation(b, {1, 0, 0}), west = map.irradiation(b, {-1, 0, 0});
    EXPECT_NEAR(east, west, 0.01 * east);
  }
  // Mirror columns about the N-S line (x ↔ width-1-x) in the diffuse band.
  double diff = 0, total = 0;
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      diff +=
          std::abs(map.value(ExposureBand::diffuse, x, y) - map.value(ExposureBand::diffuse, map.width() - 1 - x, y));
      total += map.value(ExposureBand::diffuse, x, y);
    }
  }
  EXPECT_LT(diff / total, 0.02);
}

TEST(ExposureMap, AnnualSunBandPeaksAtSolsticeDeclinations) {
  const double lat = 30.0;
  const auto steps = days(lat, 0.0, "2023-01-01T00:00Z", "2024-01-01T00:00Z", 1800);
  ExposureOptions o;
  o.width = 512;
  o.height = 256;
  const ExposureMap map = integrate_exposure(*make_isotropic_sky(make_preetham_sky(2.5)), steps, o);
  // Histogram the direct energy by the declination each direction corresponds to.
  constexpr int kBins = 120;  // 0.5° from -30° to +30°
  std::vector<double> hist(kBins, 0.0);
  for (int y = 0; y < map.height(); ++y) {
    for (int x = 0; x < map.width(); ++x) {
      const double z = map.zenith_of_row(y + 0.5), a = map.azimuth_of_column(x + 0.5);
      const double dec =
          std::asin(std::sin(lat * kDeg) * std::cos(z) + std::cos(lat * kDeg) * std::sin(z) * std::cos(a));
      const int bin = static_cast<int>(std::floor((dec / kDeg + 30.0) * 2.0));
      if (bin >= 0 && bin < kBins) hist[bin] += map.value(ExposureBand::direct, x, y) * map.cell_solid_angle(y);
    }
  }
  auto peak = [&](int lo, int hi) {
    int best = lo;
    for (int i = lo; i < hi; ++i) best = hist[i] > hist[best] ? i : best;
    return (best + 0.5) / 2.0 - 30.0;
  };
  EXPECT_NEAR(peak(0, kBins / 2), -23.44, 1.0);
  EXPECT_NEAR(peak(kBins / 2, kBins), 23.44, 1.0);
}

TEST(ExposureMap, PyramidLevelZeroIsExactAndCoarseLevelsClose) {
  const auto steps = days(45.0, 7.0, "2024-06-01T00:00Z", "2024-06-02T00:00Z");
  ExposureOptions o;
  o.width = 128;
  o.height = 64;
  const ExposureMap map = integrate_exposure(*make_preetham_sky(3.0), steps, o);
  const ExposurePyramid pyramid(map);
  EXPECT_EQ(pyramid.levels(), 8);
  const Direction south{0, -0.7071, 0.7071};
  const std::vector<float> horizon(16, static_cast<float>(10 * kDeg));
  for (ExposureBand b : {ExposureBand::direct, ExposureBand::diffuse, ExposureBand::global}) {
    const double exact = map.irradiation(b, south, horizon);
    EXPECT_NEAR(pyramid.irradiation(b, south, horizon, 0), exact, 1e-9 * exact);
    EXPECT_NEAR(pyramid.irradiation(b, south, horizon, 2), exact, 0.05 * exact);
  }
  // A horizon at the zenith hides everything.
  EXPECT_EQ(map.irradiation(ExposureBand::global, kUp, std::vector<float>(8, 1.6f)), 0.0);
}

void expect_reproduces_epw(const std::string& relative) {
  SKYVIEW_REQUIRE_SHARED(path, relative);
  const EpwFile file = read_epw(path);
  Site site;
  site.latitude_deg = file.location.latitude_deg;
  site.longitude_deg = file.location.longitude_deg;
  site.elevation_m = file.location.elevation_m;
  const auto steps = epw_steps(file, site);
  ExposureOptions o;
  o.width = 256;
  o.height = 128;
  const ExposureMap map = integrate_exposure(*make_perez_all_weather_sky(), steps, o);
  double ghi = 0, dhi = 0, beam = 0;
  for (const auto& r : file.records) {
    ghi += r.global_horizontal;
    dhi += r.diffuse_horizontal;
  }
  for (const auto& s : steps) {
    if (s.conditions.sun_zenith < std::numbers::pi / 2)
      beam += s.conditions.direct_normal * std::cos(s.conditions.sun_zenith);
  }
  const double map_diffuse = map.irradiation(ExposureBand::diffuse, kUp);
  const double map_direct = map.irradiation(ExposureBand::direct, kUp);
  EXPECT_NEAR(map_diffuse, dhi, 0.02 * dhi) << relative;
  EXPECT_NEAR(map_diffuse + map_direct, ghi, 0.02 * ghi) << relative;
  EXPECT_NEAR(map_direct, beam, 0.002 * beam) << relative;
  std::printf("[ sky      ] %s: DHI map %+.4f %%, GHI map %+.4f %% vs file\n", relative.c_str(),
              100 * (map_diffuse / dhi - 1), 100 * ((map_diffuse + map_direct) / ghi - 1));
}

TEST(ExposureMap, PerezEpwReproducesChicagoYear) { expect_reproduces_epw("weather/chicago.epw"); }
TEST(ExposureMap, PerezEpwReproducesMannheimYear) { expect_reproduces_epw("weather/mannheim.epw"); }
TEST(ExposureMap, PerezEpwReproducesPvgisYear) { expect_reproduces_epw("weather/pvgis_tmy_45N_8E.epw"); }

TEST(ExposureMap, EpwPeriodRepeatsTheTypicalYear) {
  SKYVIEW_REQUIRE_SHARED(path, "weather/mannheim.epw");
  const EpwFile file = read_epw(path);
  Site site;
  site.latitude_deg = file.location.latitude_deg;
  site.longitude_deg = file.location.longitude_deg;
  const auto june = epw_steps(
      file, site, TimePeriod{parse_time("2030-06-01T00:00Z").unix_utc, parse_time("2030-07-01T00:00Z").unix_utc});
  EXPECT_EQ(june.size(), 30u * 24u);
}

TEST(ExposureMap, RejectsBadSizes) { EXPECT_ANY_THROW(ExposureMap(0, 10)); }

}  // namespace
}  // namespace skyview
