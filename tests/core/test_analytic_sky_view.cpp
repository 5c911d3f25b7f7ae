// Analytic cases with known sky-view factors, for every sampling-based method.
#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <random>
#include <string>
#include <utility>

#include "test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

class AnalyticCase : public ::testing::TestWithParam<std::string> {};

TEST_P(AnalyticCase, FlatPlaneAtEverestHeightWithTinyCellsIsOpenSky) {
  // 8848.123 m stored as float32 in a GeoTIFF with 5 cm cells: heights relative to the observer
  // are formed in double, so nothing above the horizon appears out of rounding.
  const std::string dir = temp_dir("flat-" + GetParam());
  Terrain flat = rasterize([](double, double) { return 0.0; }, 101, 101, local_grid(101, 101, 0.05), 8848.123);
  write_terrain(dir + "/flat.tif", flat, {});
  const Terrain t = read_terrain(dir + "/flat.tif", {});
  EXPECT_NEAR(t.absolute_height(50, 50), 8848.123, 1e-3);
  HorizonParams p;
  p.radius = 2.0;
  const CellResult r = run_cell(t, 50, 50, GetParam(), p);
  EXPECT_NEAR(r.svf, 1.0, 1e-6);
  EXPECT_NEAR(r.sky_visibility, 1.0, 1e-6);
  EXPECT_NEAR(r.svf_surface, 1.0, 1e-6);
  // Grazing rays of the ray-cast reference see its eye lift (64 float steps of the mesh extent)
  // as a dip of about 1e-3 degrees at the 2 m radius.
  EXPECT_NEAR(r.openness_positive, 90.0, 3e-3);
  EXPECT_NEAR(r.openness_negative, 90.0, 3e-3);
}

TEST_P(AnalyticCase, CircularPitBottomCentre) {
  // svf = cos²(atan(h/r)), sky visibility = 1 - sin(atan(h/r)) at the bottom centre.
  for (double depth : {10.0, 20.0, 40.0}) {
    const double r = 20.0, cell = 0.1;
    const int n = 2 * static_cast<int>(22.0 / cell) + 1;
    const Terrain t = rasterize(circular_pit(r, depth), n, n, local_grid(n, n, cell));
    HorizonParams p;
    p.directions = 64;
    p.samples = 256;
    p.radius = 30.0;
    const CellResult res = run_cell(t, n / 2, n / 2, GetParam(), p);
    const double a = std::atan(depth / r);
    EXPECT_NEAR(res.svf, std::cos(a) * std::cos(a), 0.005) << "depth " << depth;
    EXPECT_NEAR(res.sky_visibility, 1.0 - std::sin(a), 0.005) << "depth " << depth;
    EXPECT_NEAR(res.svf_surface, res.svf, 1e-6) << "flat floor: surface and horizontal svf agree";
    EXPECT_NEAR(res.openness_positive, 90.0 - a / kDeg, 0.3);
  }
}

TEST_P(AnalyticCase, TiltedPlaneSurfaceSvfIsOnePlusCosOverTwo) {
  for (double slope_deg : {10.0, 30.0, 45.0, 60.0}) {
    const double beta = slope_deg * kDeg;
    const Terrain t = rasterize(tilted_plane(beta, 0.7), 201, 201, local_grid(201, 201, 1.0));
    HorizonParams p;
    p.directions = 64;
    p.radius = 50.0;
    const CellResult r = run_cell(t, 100, 100, GetParam(), p);
    EXPECT_NEAR(r.svf_surface, 0.5 * (1.0 + std::cos(beta)), 2e-3) << slope_deg << " degrees";
  }
}

// A tilted plane with its outer cells, a nodata hole and a lone nodata cell beside the edge:
// every valid cell still sits on the plane, so its normal and svf_surface are the plane's.
Terrain holed_tilted_plane(double beta, double aspect, int n) {
  Terrain t = rasterize(tilted_plane(beta, aspect), n, n, local_grid(n, n, 1.0));
  for (int r = n / 2 - 2; r <= n / 2 + 2; ++r)
    for (int c = n / 2 - 1; c <= n / 2 + 3; ++c) t.heights(c, r) = NAN;
  t.heights(1, n - 2) = NAN;
  return t;
}

TEST(HornNormal, IsThePlanesAtEdgesCornersAndBesideNodata) {
  const double beta = 30 * kDeg, aspect = 0.7;
  const int n = 21;
  const Terrain t = holed_tilted_plane(beta, aspect, n);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      if (!t.valid(c, r)) continue;
      double slope = 0, az = 0;
      horn_slope_aspect(t, c, r, slope, az);
      ASSERT_NEAR(slope, beta, 1e-6) << "cell " << c << "," << r;
      ASSERT_NEAR(az, aspect, 1e-6) << "cell " << c << "," << r;
    }
}

SkyViewProducts whole_field(const Terrain& t, const std::string& name, HorizonParams p) {
  const std::string method = engine_method(name, p);
  if (method == "sweep") p.radius = 0.0;
  if (method == "raycast") p.rays = 0;
  auto engine = make_horizon_engine(method, p);
  HorizonField field;
  ProgressCounter progress;
  const Window w = Window::whole(t);
  engine->compute(t, w, field, progress);
  return sky_view_products(t, w, field, engine->radius(), EdgeMode::open);
}

TEST_P(AnalyticCase, TiltedPlaneSurfaceSvfHoldsAtEdgesAndBesideNodata) {
  const double beta = 30 * kDeg;
  const int n = 41;
  const Terrain t = holed_tilted_plane(beta, 0.7, n);
  HorizonParams p;
  p.directions = 64;
  p.radius = 60.0;
  const SkyViewProducts out = whole_field(t, GetParam(), p);
  int checked = 0;
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      if (!t.valid(c, r)) continue;
      ASSERT_NEAR(out.svf_surface(c, r), 0.5 * (1.0 + std::cos(beta)), 2e-3) << "cell " << c << "," << r;
      ++checked;
    }
  EXPECT_EQ(checked, n * n - 26);
}

// The edge ring continues a plane up to the raster's extent (half a cell beyond the outer centres),
// where every track ends (track_box.h). A copy of the boundary cells stood above a slope falling
// off the raster (on a 41² plane, svf 0.921–0.922 instead of 0.933 on the downhill edges) and gave
// no slope on the uphill ones (0.970–0.979); with the slope continued, every cell one or more in
// from the edge reads the centre's svf to 2e-7 and its lowest angles to 4e-5°, all engines. The
// boundary cells themselves see nothing where their track crosses no row or column line before
// the extent (outward, more than 26.6° off the edge): until Dec 7 the ring's centres, one cell
// beyond, counted as terrain there and every boundary cell read the centre's 0.9330; now the exact
// methods read 0.9333 to 1.0000 on them. The sampled method's samples between crossings still read
// the plane in the half-cell strip: 0.9330 on the boundary too.
TEST_P(AnalyticCase, TiltedPlaneSvfIsTheSameOnItsEdgesAsInside) {
  const int n = 31;
  const Terrain t = rasterize(tilted_plane(30 * kDeg, 0.7), n, n, local_grid(n, n, 1.0));
  HorizonParams p;
  p.directions = 64;
  p.radius = 60.0;
  p.lower = true;
  const SkyViewProducts out = whole_field(t, GetParam(), p);
  const float inside = out.svf(n / 2, n / 2), lowest_inside = out.openness_negative(n / 2, n / 2);
  for (int r = 1; r < n - 1; ++r)
    for (int c = 1; c < n - 1; ++c) {
      ASSERT_NEAR(out.svf(c, r), inside, 2e-4) << "cell " << c << "," << r;
      ASSERT_NEAR(out.openness_negative(c, r), lowest_inside, 0.05) << "cell " << c << "," << r;
    }
  // Measured Dec 7, the same for march, sweep (one or two far lines) and ray cast.
  struct Edge {
    int col, row;
    double svf;
  };
  const bool exact = std::string(GetParam()) != "sampled";
  for (const Edge& e : {Edge{0, 0, 0.976615}, Edge{15, 0, 0.933298}, Edge{30, 0, 0.934585}, Edge{0, 15, 0.976615},
                        Edge{30, 15, 0.934300}, Edge{0, 30, 1.0}, Edge{15, 30, 0.982809}, Edge{30, 30, 0.982809}}) {
    EXPECT_NEAR(out.svf(e.col, e.row), exact ? e.svf : inside, 2e-4) << "cell " << e.col << "," << e.row;
  }
  for (int i = 0; i < n; ++i) {
    for (const auto& [c, r] : {std::pair{i, 0}, std::pair{i, n - 1}, std::pair{0, i}, std::pair{n - 1, i}}) {
      EXPECT_GE(out.svf(c, r), inside - 2e-4) << "cell " << c << "," << r;  // open outward, never shaded
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, AnalyticCase, ::testing::Values("march", "sampled", "sweep", "sweep2", "raycast"));

class StreetCanyon : public ::testing::TestWithParam<std::string> {};

TEST_P(StreetCanyon, FloorCentreMatchesInfiniteCanyon) {
  // Infinite symmetric canyon of width W, height H: svf = cos(atan(2H/W)).
  for (double ratio : {0.5, 1.0, 2.0}) {
    const double w = 10.0, h = ratio * w, cell = 0.25;
    const int cols = 65, rows = 2 * static_cast<int>(120.0 / cell) + 1;
    const Terrain t = rasterize(street_canyon(w, h), cols, rows, local_grid(cols, rows, cell));
    HorizonParams p;
    p.directions = 64;
    p.radius = 150.0;
    const CellResult r = run_cell(t, cols / 2, rows / 2, GetParam(), p);
    EXPECT_NEAR(r.svf, std::cos(std::atan(2.0 * ratio)), 0.01) << "H/W " << ratio;
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, StreetCanyon, ::testing::Values("march", "sweep", "sweep2", "raycast"));

TEST(GroundFrame, PitInUtmAndInDegreesAtLatitude60GivesTheSameValues) {
  const double r = 20.0, depth = 10.0, cell = 0.2;
  const int n = 2 * static_cast<int>(22.0 / cell) + 1;
  // UTM zone 33N around 60 N 15 E.
  GeoReference utm = local_grid(n, n, cell);
  utm.geotransform[0] += 500000.0;
  utm.geotransform[3] += 6651411.0;
  utm.crs_wkt = wkt_of("EPSG:32633");
  // The same ground in EPSG:4326 with cells of about the same size.
  const GeographicLib::Geodesic& wgs = GeographicLib::Geodesic::WGS84();
  double lat2, lon2;
  wgs.Direct(60.0, 15.0, 0.0, cell, lat2, lon2);
  const double dlat = lat2 - 60.0;
  wgs.Direct(60.0, 15.0, 90.0, cell, lat2, lon2);
  const double dlon = lon2 - 15.0;
  GeoReference geo;
  geo.has_geotransform = true;
  geo.geotransform = {15.0 - 0.5 * n * dlon, dlon, 0, 60.0 + 0.5 * n * dlat, 0, -dlat};
  geo.crs_wkt = wkt_of("EPSG:4326");
  const Terrain tu = rasterize(circular_pit(r, depth), n, n, utm);
  const Terrain tg = rasterize(circular_pit(r, depth), n, n, geo);
  EXPECT_TRUE(tg.frame.is_geographic());
  HorizonParams p;
  p.directions = 64;
  p.radius = 30.0;
  const CellResult a = run_cell(tu, n / 2, n / 2, "march", p);
  const CellResult b = run_cell(tg, n / 2, n / 2, "march", p);
  const double expected = std::pow(std::cos(std::atan(depth / r)), 2);
  EXPECT_NEAR(a.svf, expected, 0.005);
  EXPECT_NEAR(a.svf, b.svf, 0.005);
  EXPECT_NEAR(a.sky_visibility, b.sky_visibility, 0.005);
  // A cell off-centre on the pit floor: azimuths must be true, not grid, for this to agree.
  const CellResult a2 = run_cell(tu, n / 2 + 40, n / 2 - 25, "march", p);
  const CellResult b2 = run_cell(tg, n / 2 + 40, n / 2 - 25, "march", p);
  EXPECT_NEAR(a2.svf, b2.svf, 0.005);
}

// The per-sector sum of sky_view.h written out as it reads, with library sines, cosines and
// arctangents in every sector: what svf_tilted computes with polynomials (fast_atan's error is
// below 1e-11 rad, the sine's and cosine's below 1e-15).
double svf_tilted_as_written(const std::vector<float>& h, double rotation, double slope, double aspect) {
  const int n = static_cast<int>(h.size());
  const double delta = 2.0 * M_PI / n, sum_half = std::sin(0.5 * delta);
  double sum = 0.0;
  for (int k = 0; k < n; ++k) {
    const double cos_rel = std::cos(sector_azimuth(k, n) + rotation - aspect);
    const double t = std::atan(-std::tan(slope) * cos_rel);
    const double H = std::max({static_cast<double>(h[k]), t, 0.0});
    sum += std::cos(slope) * std::cos(H) * std::cos(H) * delta / (2.0 * M_PI) +
           std::sin(slope) * cos_rel * sum_half * (0.5 * M_PI - H - std::sin(H) * std::cos(H)) / M_PI;
  }
  return std::clamp(sum, 0.0, 1.0);
}

TEST(SkyViewFormulas, TiltedSurfaceMatchesTheFormulaAsWritten) {
  // Horizons below and above the surface's own horizon, slopes up to 80 degrees, any aspect and
  // rotation: the branch that takes the surface's horizon must pick exactly the sectors where it
  // is the highest of the three.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int surface_wins = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int n = 4 + trial % 61;
    std::vector<float> h(n);
    for (float& x : h) x = static_cast<float>((u(rng) * 1.4 - 0.5) * M_PI / 2);
    const double slope = u(rng) * 80.0 * kDeg, aspect = u(rng) * 2 * M_PI, rotation = (u(rng) - 0.5) * 0.4;
    for (int k = 0; k < n; ++k) {
      surface_wins += std::atan(-std::tan(slope) * std::cos(sector_azimuth(k, n) + rotation - aspect)) >
                      std::max(0.0, static_cast<double>(h[k]));
    }
    ASSERT_NEAR(svf_tilted(h.data(), n, rotation, slope, aspect), svf_tilted_as_written(h, rotation, slope, aspect),
                1e-10)
        << "trial " << trial;
  }
  EXPECT_GT(surface_wins, 5000) << "the test must cover sectors where the surface's own horizon is the highest";
}

TEST(SkyViewFormulas, TiltedSurfaceWithPlaneHorizonsConvergesToAnalytic) {
  // Feeding the exact plane horizon per sector isolates the per-sector integration error.
  const double beta = 40.0 * kDeg, aspect = 1.1;
  for (int n : {8, 32, 128}) {
    std::vector<float> h(n);
    for (int k = 0; k < n; ++k)
      h[k] = static_cast<float>(std::atan(-std::tan(beta) * std::cos(sector_azimuth(k, n) - aspect)));
    const double err = std::abs(svf_tilted(h.data(), n, 0.0, beta, aspect) - 0.5 * (1 + std::cos(beta)));
    EXPECT_LT(err, n == 8 ? 0.02 : (n == 32 ? 2e-3 : 2e-4)) << n << " sectors";
  }
  std::vector<float> flat(16, 0.0f);
  EXPECT_DOUBLE_EQ(svf_horizontal(flat.data(), 16), 1.0);
  EXPECT_DOUBLE_EQ(sky_visibility(flat.data(), 16), 1.0);
  std::vector<float> wall(16, static_cast<float>(M_PI / 2));
  EXPECT_NEAR(svf_horizontal(wall.data(), 16), 0.0, 1e-12);
}

}  // namespace
