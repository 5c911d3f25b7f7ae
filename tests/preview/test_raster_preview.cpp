// The preview module: ramps, the stretch, nodata, and the world file that lays the picture on its
// cells (docs/previews.md).
#include <gtest/gtest.h>

#include <ogr_spatialref.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "preview_test_support.h"
#include "skyview/core/error.h"
#include "skyview/preview/raster_preview.h"
#include "temp_dir.h"

namespace skyview::test {
namespace {

void expect_colour(const std::array<std::uint8_t, 3>& c, int r, int g, int b) {
  EXPECT_NEAR(c[0], r, 1);
  EXPECT_NEAR(c[1], g, 1);
  EXPECT_NEAR(c[2], b, 1);
}

// Perceived lightness (Rec. 709 luma) of a pixel.
double luma(const std::array<int, 4>& p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

GeoReference sweref(double x0, double y0, double cell) {
  GeoReference g;
  g.geotransform = {x0, cell, 0, y0, 0, -cell};
  g.has_geotransform = true;
  OGRSpatialReference crs;
  crs.importFromEPSG(3006);
  char* wkt = nullptr;
  crs.exportToWkt(&wkt);
  g.crs_wkt = wkt;
  CPLFree(wkt);
  return g;
}

TEST(ColourRamp, EndsAreMatplotlibs) {
  // matplotlib's _cm_listed tables, first and last entries times 255.
  expect_colour(ramp_colour(ColourRamp::viridis, 0.0), 68, 1, 84);
  expect_colour(ramp_colour(ColourRamp::viridis, 1.0), 253, 231, 37);
  expect_colour(ramp_colour(ColourRamp::magma, 0.0), 0, 0, 4);
  expect_colour(ramp_colour(ColourRamp::magma, 1.0), 252, 253, 191);
  expect_colour(ramp_colour(ColourRamp::cividis, 0.0), 0, 34, 78);
  expect_colour(ramp_colour(ColourRamp::cividis, 1.0), 254, 232, 56);
  // Diverging: white at zero (the middle), blue below, red above.
  expect_colour(ramp_colour(ColourRamp::diverging, 0.5), 247, 247, 247);
  expect_colour(ramp_colour(ColourRamp::diverging, 0.0), 5, 48, 97);
  expect_colour(ramp_colour(ColourRamp::diverging, 1.0), 103, 0, 31);
  expect_colour(ramp_colour(ColourRamp::grey, 0.5), 128, 128, 128);
  // Clamped outside [0, 1].
  expect_colour(ramp_colour(ColourRamp::viridis, 7.0), 253, 231, 37);
}

TEST(ColourRamp, SuitsTheQuantity) {
  EXPECT_EQ(ramp_for_band("svf", "1"), ColourRamp::viridis);
  EXPECT_EQ(ramp_for_band("sky_visibility", "1"), ColourRamp::viridis);
  EXPECT_EQ(ramp_for_band("horizon_azimuth_90", "degree"), ColourRamp::cividis);
  EXPECT_EQ(ramp_for_band("openness_positive", "degree"), ColourRamp::cividis);
  EXPECT_EQ(ramp_for_band("height", "metre"), ColourRamp::magma);
  EXPECT_EQ(ramp_for_band("total", "kWh m-2"), ColourRamp::magma);
  EXPECT_EQ(ramp_for_band("sun_hours", "hours"), ColourRamp::magma);
  EXPECT_EQ(ramp_for_band("svf_difference", "1"), ColourRamp::diverging);
  EXPECT_EQ(ramp_for_band("sunlit", "1"), ColourRamp::grey);
}

TEST(PreviewRange, StretchesToThePercentiles) {
  // 0.950, 0.951, ... 1.000 (51 values, each 20 times) and nodata: the 2nd and 98th percentiles.
  Grid<float> v(51, 21, NAN);
  for (int r = 0; r < 20; ++r)
    for (int c = 0; c < 51; ++c) v(c, r) = 0.95f + 0.001f * c;
  PreviewSpec spec;
  const auto [lo, hi] = preview_range(v, spec);
  EXPECT_NEAR(lo, 0.951, 1e-6);
  EXPECT_NEAR(hi, 0.999, 1e-6);
  // A mast among the roofs: one cell far above moves the top of the ramp by one rank, not to it.
  v(0, 20) = 300.0f;
  EXPECT_NEAR(preview_range(v, spec).second, 1.0, 1e-6);
  // Given limits win.
  spec.range = std::pair{0.0, 1.0};
  EXPECT_EQ(preview_range(v, spec), (std::pair{0.0, 1.0}));
}

TEST(PreviewRange, DivergingIsSymmetricAndFlatIsWidened) {
  Grid<float> v(100, 1);
  for (int c = 0; c < 100; ++c) v(c, 0) = static_cast<float>(c - 20);  // -20 .. 79
  PreviewSpec spec;
  spec.ramp = ColourRamp::diverging;
  const auto [lo, hi] = preview_range(v, spec);
  EXPECT_NEAR(hi, 77.0, 1e-9);  // the 98th percentile of |v|
  EXPECT_EQ(lo, -hi);
  Grid<float> flat(10, 10, 1.0f);
  spec.ramp = ColourRamp::viridis;
  const auto [a, b] = preview_range(flat, spec);
  EXPECT_LT(a, 1.0);
  EXPECT_GT(b, 1.0);
  EXPECT_NEAR(b - a, 0.02, 1e-9);
  Grid<float> none(4, 4, NAN);
  EXPECT_EQ(preview_range(none, spec), (std::pair{0.0, 1.0}));
}

TEST(RasterPreview, OpenTerrainIsNotWhite) {
  // An svf of 0.95 to 1 (open land): the old fixed 0-1 grey drew it 242 to 255, nearly white.
  const std::string dir = temp_dir("preview");
  Grid<float> v(200, 100);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> open(0.95f, 1.0f);
  for (float& x : v.values()) x = open(rng);
  PreviewSpec spec;
  spec.band = "svf";
  spec.unit = "1";
  spec.title = "svf - open.tif";
  spec.georef = sweref(319000, 6400000, 1.0);
  write_raster_preview(dir + "/p.png", v, spec, false);
  const PreviewPicture p = read_preview(dir + "/p.png");
  ASSERT_GT(p.width, 200);
  // Over the map, the darkest and lightest pixels are far apart, and most are not near-white.
  double darkest = 255, lightest = 0;
  int near_white = 0, counted = 0;
  for (int r = 0; r < 100; ++r) {
    for (int c = 0; c < 200; ++c) {
      const auto [x, y] = pixel_at(p, 319000 + c + 0.5, 6400000 - r - 0.5);
      const double l = luma(p.at(x, y));
      darkest = std::min(darkest, l);
      lightest = std::max(lightest, l);
      near_white += l > 230;
      ++counted;
    }
  }
  EXPECT_LT(darkest, 60.0);
  EXPECT_GT(lightest, 190.0);
  EXPECT_LT(near_white, counted / 10);
  EXPECT_EQ(p.band, "svf");
  EXPECT_EQ(p.ramp, "viridis");
}

TEST(RasterPreview, WorldFileLaysEachCellOnItsGround) {
  const std::string dir = temp_dir("preview");
  // 60 x 40 cells of 2 m at (319000, 6400000), values a ramp along columns, a nodata block.
  Grid<float> v(60, 40);
  for (int r = 0; r < 40; ++r)
    for (int c = 0; c < 60; ++c) v(c, r) = static_cast<float>(c) / 59.0f;
  for (int r = 10; r < 20; ++r)
    for (int c = 30; c < 40; ++c) v(c, r) = NAN;
  PreviewSpec spec;
  spec.band = "svf";
  spec.unit = "1";
  spec.range = std::pair{0.0, 1.0};
  spec.georef = sweref(319000, 6400000, 2.0);
  write_raster_preview(dir + "/p.png", v, spec, false);
  EXPECT_TRUE(std::filesystem::exists(dir + "/p.pgw"));
  const PreviewPicture p = read_preview(dir + "/p.png");
  ASSERT_TRUE(p.has_geotransform);
  EXPECT_EQ(p.epsg, "3006");
  EXPECT_EQ(p.bands, 4);
  // Small rasters are drawn with whole pixels per cell: 2 m / 7 per pixel (420 / 60 = 7).
  EXPECT_NEAR(p.geotransform[1], 2.0 / 7, 1e-9);
  EXPECT_NEAR(p.geotransform[5], -2.0 / 7, 1e-9);
  for (int r : {0, 5, 39}) {
    for (int c : {0, 13, 59}) {
      const auto [x, y] = pixel_at(p, 319000 + 2.0 * c + 1.0, 6400000 - 2.0 * r - 1.0);
      const auto want = ramp_colour(ColourRamp::viridis, v(c, r));
      const auto got = p.at(x, y);
      EXPECT_NEAR(got[0], want[0], 1) << c << "," << r;
      EXPECT_NEAR(got[1], want[1], 1) << c << "," << r;
      EXPECT_NEAR(got[2], want[2], 1) << c << "," << r;
      EXPECT_EQ(got[3], 255);
    }
  }
  // Nodata is transparent.
  const auto [nx, ny] = pixel_at(p, 319000 + 2.0 * 35 + 1.0, 6400000 - 2.0 * 15 - 1.0);
  EXPECT_EQ(p.at(nx, ny)[3], 0);
  // The legend and title sit outside the map, on opaque white.
  EXPECT_EQ(p.at(2, 2), (std::array<int, 4>{255, 255, 255, 255}));
}

TEST(RasterPreview, LargeRastersAreAveragedAndExistingFilesKept) {
  const std::string dir = temp_dir("preview");
  Grid<float> v(3000, 10, 0.25f);
  for (int c = 1500; c < 3000; ++c) v(c, 0) = 0.75f;
  PreviewSpec spec;
  spec.band = "svf";
  spec.range = std::pair{0.0, 1.0};
  spec.georef = sweref(0, 0, 1.0);
  write_raster_preview(dir + "/p.png", v, spec, false);
  const PreviewPicture p = read_preview(dir + "/p.png");
  // 3 cells per pixel: 1000 pixels of map across.
  EXPECT_NEAR(p.geotransform[1], 3.0, 1e-12);
  EXPECT_THROW(write_raster_preview(dir + "/p.png", v, spec, false), Error);
  // No stray files: the picture, its world file and its .aux.xml.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 3);
}

}  // namespace
}  // namespace skyview::test
