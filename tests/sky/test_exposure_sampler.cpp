// The Section 6 sampler against the full-resolution integral of the same map: open horizontal and
// tilted surfaces, pits, opening angles, slices facing away, and cached against on-the-fly samples.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "sky_test_support.h"
#include "skyview/core/error.h"
#include "skyview/sky/exposure_map.h"
#include "skyview/sky/exposure_pyramid.h"
#include "skyview/sky/exposure_sampler.h"
#include "skyview/sky/exposure_steps.h"
#include "skyview/sky/sky_models.h"
#include "skyview/solar/time_parse.h"

namespace skyview {
namespace {

using sky_test::kDeg;
constexpr Direction kUp{0, 0, 1};

// A year at 30° N with two-hour steps on a 128 × 128 map: the sun's band and a clear sky, cheap.
const ExposureMap& year_map() {
  static const ExposureMap map = [] {
    Site site;
    site.latitude_deg = 30.0;
    site.longitude_deg = 10.0;
    const auto steps =
        regular_steps(site, parse_time("2023-01-01T00:00Z").unix_utc, parse_time("2024-01-01T00:00Z").unix_utc, 7200.0);
    ExposureOptions o;
    o.width = o.height = 128;
    return integrate_exposure(*make_preetham_sky(2.5), steps, o);
  }();
  return map;
}

Direction tilted(double slope, double aspect) {
  return {std::sin(slope) * std::sin(aspect), std::sin(slope) * std::cos(aspect), std::cos(slope)};
}

std::size_t n_open(const Direction&) { return 64; }

void expect_close(const SkyExposure& got, const ExposureMap& map, const Direction& n, std::span<const float> horizon,
                  double tolerance) {
  const double direct = map.irradiation(ExposureBand::direct, n, horizon);
  const double diffuse = map.irradiation(ExposureBand::diffuse, n, horizon);
  EXPECT_NEAR(got.direct, direct, tolerance * (direct + diffuse)) << "direct";
  EXPECT_NEAR(got.diffuse, diffuse, tolerance * (direct + diffuse)) << "diffuse";
  EXPECT_NEAR(got.total(), direct + diffuse, tolerance * (direct + diffuse)) << "total";
}

TEST(ExposureSampler, OpenHorizontalPlaneReceivesTheMapsHorizontalIntegral) {
  const ExposureMap& map = year_map();
  const ExposurePyramid pyramid(map);
  for (int n : {8, 16, 32}) {
    const ExposureSampler sampler(pyramid, n);
    const std::vector<float> open(n, 0.0f);
    const SkyExposure e = sampler.exposure(kUp, open);
    const double expected = map.irradiation(ExposureBand::global, kUp);
    EXPECT_GT(expected, 1.5e6);  // Wh/m² in a clear year at 30° N
    // The moments make the horizontal cosine exact: only the map's float storage remains.
    EXPECT_NEAR(e.total(), expected, 1e-5 * expected) << n << " directions";
    EXPECT_NEAR(e.direct, map.irradiation(ExposureBand::direct, kUp), 1e-5 * expected);
  }
}

TEST(ExposureSampler, TiltedOpenSurfacesAgreeWithTheFullIntegral) {
  const ExposureMap& map = year_map();
  const ExposurePyramid pyramid(map);
  const ExposureSampler sampler(pyramid, 16);
  const std::vector<float> open(16, 0.0f);
  for (double slope : {30.0, 60.0, 90.0}) {
    for (double aspect : {0.0, 90.0, 180.0, 225.0}) {
      SCOPED_TRACE(testing::Message() << "slope " << slope << " aspect " << aspect);
      const Direction n = tilted(slope * kDeg, aspect * kDeg);
      expect_close(sampler.exposure(n, open), map, n, {}, 0.02);
    }
  }
}

TEST(ExposureSampler, HorizonsCutTheSkyAsTheFullIntegralDoes) {
  const ExposureMap& map = year_map();
  const ExposurePyramid pyramid(map);
  const int n = 16;
  const ExposureSampler sampler(pyramid, n);
  // A pit (the same horizon all round) and an uneven skyline: a wall to the south, open north.
  for (double h : {10.0, 30.0, 50.0}) {
    SCOPED_TRACE(testing::Message() << "pit horizon " << h);
    const std::vector<float> pit(n, static_cast<float>(h * kDeg));
    expect_close(sampler.exposure(kUp, pit), map, kUp, pit, 0.02);
  }
  std::vector<float> skyline(n);
  for (int k = 0; k < n; ++k) skyline[k] = static_cast<float>(std::max(0.0, 40.0 * -std::cos(2 * M_PI * k / n)) * kDeg);
  expect_close(sampler.exposure(kUp, skyline), map, kUp, skyline, 0.03);
  const Direction south_roof = tilted(35 * kDeg, 180 * kDeg);
  expect_close(sampler.exposure(south_roof, skyline), map, south_roof, skyline, 0.03);
}

TEST(ExposureSampler, OpeningAngleLimitsTheSliceFromAbove) {
  const ExposureMap& map = year_map();
  const ExposurePyramid pyramid(map);
  const int n = 16;
  const ExposureSampler sampler(pyramid, n);
  // Sky between 20° and 60° everywhere = sky above 20° minus sky above 60°.
  const std::vector<float> low(n, static_cast<float>(20 * kDeg)), high(n, static_cast<float>(60 * kDeg));
  const SkyExposure band = sampler.exposure(kUp, low, high);
  const double expected =
      map.irradiation(ExposureBand::global, kUp, low) - map.irradiation(ExposureBand::global, kUp, high);
  EXPECT_GT(expected, 0.0);
  EXPECT_NEAR(band.total(), expected, 0.02 * expected);
  // An opening at or below the horizon leaves nothing.
  EXPECT_EQ(sampler.exposure(kUp, high, low).total(), 0.0);
}

TEST(ExposureSampler, SlicesFacingAwayAreDiscarded) {
  const ExposureMap& map = year_map();
  const ExposurePyramid pyramid(map);
  const int n = 16;
  const ExposureSampler sampler(pyramid, n);
  // A vertical wall facing north: no slice of the southern half faces it.
  const Direction north_wall = tilted(90 * kDeg, 0.0);
  std::vector<float> horizon(n, 0.0f);
  SkyExposure only_north;
  for (int k = 0; k < n; ++k) {
    const double azimuth = 2 * M_PI * k / n;
    std::vector<SkyExposure> out(1);
    sampler.add_slice(k, horizon[k], static_cast<float>(M_PI / 2), {&north_wall, 1}, out);
    if (std::cos(azimuth) < -1e-9) {
      EXPECT_EQ(out[0].total(), 0.0) << "slice " << k;
    }
    only_north += out[0];
  }
  const SkyExposure whole = sampler.exposure(north_wall, horizon);
  EXPECT_NEAR(only_north.total(), whole.total(), 1e-9 * whole.total());
  expect_close(whole, map, north_wall, {}, 0.02);
  // A south wall at 30° N gets most of the year's beam on vertical surfaces; a north wall little.
  const SkyExposure south = sampler.exposure(tilted(90 * kDeg, M_PI), horizon);
  EXPECT_GT(south.direct, 5 * whole.direct);
}

TEST(ExposureSampler, TurnedSetsGiveTheCachedSamplersResult) {
  const ExposureMap& map = year_map();
  const ExposurePyramid pyramid(map);
  const int n = 16;
  const double turn = 0.3;
  const ExposureSampler cached(pyramid, n, turn), plain(pyramid, n);
  std::vector<float> horizon(n);
  for (int k = 0; k < n; ++k) horizon[k] = static_cast<float>((10 + 3 * k) * kDeg);
  const Direction roof = tilted(25 * kDeg, 200 * kDeg);
  const SkyExposure a = cached.exposure(roof, horizon), b = plain.exposure(roof, horizon, {}, turn);
  EXPECT_NEAR(a.direct, b.direct, 1e-9 * a.total());
  EXPECT_NEAR(a.diffuse, b.diffuse, 1e-9 * a.total());
}

TEST(ExposureSampler, OneRowSamplesIntegrateTheMapExactly) {
  const ExposureMap& map = year_map();
  const ExposurePyramid pyramid(map);
  const int n = 64;
  SamplerOptions exact;
  exact.max_sample_rows = 1;
  const ExposureSampler sampler(pyramid, n, 0.0, exact);
  EXPECT_EQ(sampler.sample_count(0.0f, static_cast<float>(M_PI / 2)), 128);
  std::vector<float> skyline(n);
  for (int k = 0; k < n; ++k) skyline[k] = static_cast<float>((20 + 15 * std::sin(3.0 * k)) * kDeg);
  // The map's own integral tests each cell's centre against its sector's horizon; one-row samples
  // cut the rows at the horizon: they differ by what the horizon's row holds, a fraction of a percent.
  for (const Direction& n : {kUp, tilted(90 * kDeg, 0.0), tilted(90 * kDeg, M_PI), tilted(70 * kDeg, 1.0)}) {
    SCOPED_TRACE(testing::Message() << "normal " << n[0] << " " << n[1] << " " << n[2]);
    expect_close(sampler.exposure(n, std::vector<float>(n_open(n), 0.0f)), map, n, {}, 1e-3);
    expect_close(sampler.exposure(n, skyline), map, n, skyline, 5e-3);
  }
}

// The paper's own reads (trilinear in the mip-map, Eqs. 8–10) on the same cases: an open plane is
// integrated well, but where a horizon cuts the sun's band the filter reaches across it.
TEST(ExposureSampler, MipmapReadsAreThePapersAndCoarserWhereHorizonsCutTheSunsBand) {
  const ExposureMap& map = year_map();
  const ExposurePyramid pyramid(map);
  SamplerOptions paper;
  paper.reads = SamplerReads::mipmap;
  const int n = 16;
  const ExposureSampler mipmap(pyramid, n, 0.0, paper), area(pyramid, n);
  const double open = map.irradiation(ExposureBand::global, kUp);
  EXPECT_NEAR(mipmap.exposure(kUp, std::vector<float>(n, 0.0f)).total(), open, 0.01 * open);
  std::vector<float> skyline(n);
  for (int k = 0; k < n; ++k) skyline[k] = static_cast<float>(45 * (1 + 0.5 * std::sin(1.7 * k)) * kDeg);
  const Direction wall = tilted(90 * kDeg, 45 * kDeg);
  const double exact = map.irradiation(ExposureBand::global, wall, skyline);
  EXPECT_GT(std::abs(mipmap.exposure(wall, skyline).total() - exact), 0.1 * exact);
  EXPECT_NEAR(area.exposure(wall, skyline).total(), exact, 0.01 * exact);  // the map's own cell-centre test
}

// Gaps read the sky above the horizon interpolated between two directions: against the map's full
// integral under a fine skyline drawn from the same lines.
TEST(ExposureSampler, GapsFollowTheHorizonInterpolatedBetweenDirections) {
  const ExposureMap& map = year_map();
  const ExposurePyramid pyramid(map);
  const int n = 16, fine = 256;  // two fine sectors per map column: each column centre on one's centre
  SamplerOptions options;
  options.gap_parts = 8;
  const ExposureSampler sampler(pyramid, n, 0.0, options);
  std::vector<float> h(n), skyline(fine);
  for (int k = 0; k < n; ++k) h[k] = static_cast<float>((25 + 20 * std::sin(2.3 * k)) * kDeg);
  for (int i = 0; i < fine; ++i) {
    const double p = static_cast<double>(i) * n / fine;  // fine sector i's centre, in directions
    const int k = static_cast<int>(p);
    skyline[i] = static_cast<float>(h[k] + (p - k) * (h[(k + 1) % n] - h[k]));
  }
  for (const Direction& normal : {kUp, tilted(40 * kDeg, 2.0)}) {
    SkyExposure sum;
    for (int k = 0; k < n; ++k) sampler.add_gap(k, h[k], h[(k + 1) % n], {&normal, 1}, {&sum, 1});
    expect_close(sum, map, normal, skyline, 0.01);
  }
  // Under a level horizon gaps and slices cover the same sky.
  const std::vector<float> level(n, static_cast<float>(30 * kDeg));
  SkyExposure gaps;
  for (int k = 0; k < n; ++k) sampler.add_gap(k, level[k], level[k], {&kUp, 1}, {&gaps, 1});
  EXPECT_NEAR(gaps.total(), sampler.exposure(kUp, level).total(), 1e-9 * gaps.total());
}

TEST(ExposureSampler, SampleCountFollowsEquation7) {
  const ExposureMap& map = year_map();
  const ExposurePyramid pyramid(map);
  // 128-cell map, 16 directions: slices 8 cells wide, the quarter turn of elevation 128 cells high.
  const ExposureSampler sampler(pyramid, 16);
  const float top = static_cast<float>(M_PI / 2);
  EXPECT_EQ(sampler.sample_count(0.0f, top), 16);
  EXPECT_EQ(sampler.sample_count(static_cast<float>(45 * kDeg), top), 8);
  EXPECT_EQ(sampler.sample_count(static_cast<float>(89.9 * kDeg), top), 1);
  EXPECT_EQ(sampler.sample_count(top, top), 0);
  EXPECT_EQ(sampler.sample_count(static_cast<float>(-0.3), top), 16);  // no sky below the horizontal
  EXPECT_EQ(ExposureSampler(pyramid, 8).sample_count(0.0f, top), 8);
  EXPECT_THROW(ExposureSampler(pyramid, 0), Error);
  EXPECT_THROW(ExposureSampler(pyramid, 129), Error);
}

}  // namespace
}  // namespace skyview
