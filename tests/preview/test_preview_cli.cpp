// --preview, --preview-range and --preview-band from the command line: the band drawn, its ramp,
// one exit code for bad values on every command that previews; and the one summary line.
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "core/cli_run.h"
#include "core/test_support.h"
#include "preview_test_support.h"
#include "skyview/preview/colour_ramp.h"
#include "skyview/synthetic/synthetic.h"

namespace skyview {
namespace {

// A 40 x 40 UTM DSM of 2 m cells (57.7 N, 15 E): a 15 m block on a plane, so that svf and
// horizons vary.
std::string write_dsm(const std::string& dir) {
  GeoReference g;
  g.geotransform = {500000.0, 2.0, 0.0, 6400000.0, 0.0, -2.0};
  g.has_geotransform = true;
  g.crs_wkt = test::wkt_of("EPSG:32633");
  const Terrain t =
      rasterize([](double e, double n) { return std::abs(e) < 10 && std::abs(n) < 6 ? 15.0 : 0.0; }, 40, 40, g);
  const std::string path = dir + "/dsm.tif";
  write_terrain(path, t, WriteOptions{});
  return path;
}

// Band `band` (1-based) of the raster at `path`.
std::vector<float> read_band(const std::string& path, int band, int& width, int& height) {
  init_gdal();
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER));
  EXPECT_TRUE(ds);
  if (!ds) return {};
  width = ds->GetRasterXSize();
  height = ds->GetRasterYSize();
  std::vector<float> v(static_cast<std::size_t>(width) * height);
  EXPECT_EQ(ds->GetRasterBand(band)->RasterIO(GF_Read, 0, 0, width, height, v.data(), width, height, GDT_Float32, 0, 0),
            CE_None);
  return v;
}

// Each valid cell of `band` of `raster` has, under it in the preview, the ramp's colour for its
// value within the preview's range.
void expect_preview_shows(const std::string& png, const std::string& raster, int band, ColourRamp ramp) {
  int w = 0, h = 0;
  const std::vector<float> v = read_band(raster, band, w, h);
  const test::PreviewPicture p = test::read_preview(png);
  ASSERT_TRUE(p.has_geotransform);
  double lo = 0, hi = 0;
  ASSERT_EQ(std::sscanf(p.range.c_str(), "%lf,%lf", &lo, &hi), 2) << p.range;
  int checked = 0;
  for (int r = 1; r < h; r += 7) {
    for (int c = 1; c < w; c += 5) {
      const float x = v[static_cast<std::size_t>(r) * w + c];
      if (std::isnan(x)) continue;
      const auto [px, py] = test::pixel_at(p, 500000.0 + 2.0 * c + 1.0, 6400000.0 - 2.0 * r - 1.0);
      const auto want = ramp_colour(ramp, (x - lo) / (hi - lo));
      const auto got = p.at(px, py);
      EXPECT_NEAR(got[0], want[0], 2) << c << "," << r << " value " << x;
      EXPECT_NEAR(got[1], want[1], 2) << c << "," << r;
      EXPECT_NEAR(got[2], want[2], 2) << c << "," << r;
      ++checked;
    }
  }
  EXPECT_GT(checked, 20);
}

// Runs without -q, so that the summary line is printed; returns stderr.
std::string run_loud(const std::string& args, const std::string& dir, int& code) {
  const std::string err = dir + "/loud.txt";
  code = std::system((std::string(SKYVIEW_EXE) + " " + args + " 2>" + err + " >/dev/null").c_str());
  std::ifstream in(err);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(PreviewCli, SkyVisibilityAloneIsTheBandDrawnAndNamed) {
  const std::string dir = test::temp_dir("preview-cli");
  const std::string dsm = write_dsm(dir);
  const test::RunResult r =
      test::run_skyview("svf " + dsm + " " + dir + "/s.tif --products sky_visibility --preview " + dir + "/p.png", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const test::PreviewPicture p = test::read_preview(dir + "/p.png");
  EXPECT_EQ(p.band, "sky_visibility");
  EXPECT_EQ(p.title, "sky_visibility - s.tif");
  EXPECT_EQ(p.ramp, "viridis");
  EXPECT_EQ(p.epsg, "32633");
  expect_preview_shows(dir + "/p.png", dir + "/s.tif", 1, ColourRamp::viridis);
}

TEST(PreviewCli, PreviewBandAndRangeChooseWhatIsDrawn) {
  const std::string dir = test::temp_dir("preview-cli");
  const std::string dsm = write_dsm(dir);
  const test::RunResult r =
      test::run_skyview("svf " + dsm + " " + dir + "/s.tif --products svf,openness_positive " + "--preview " + dir +
                            "/p.png --preview-band openness_positive " + "--preview-range 40,95",
                        dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const test::PreviewPicture p = test::read_preview(dir + "/p.png");
  EXPECT_EQ(p.band, "openness_positive");
  EXPECT_EQ(p.ramp, "cividis");
  EXPECT_EQ(p.range, "40,95");
  expect_preview_shows(dir + "/p.png", dir + "/s.tif", 2, ColourRamp::cividis);
}

TEST(PreviewCli, HorizonDrawsADirectionInDegrees) {
  const std::string dir = test::temp_dir("preview-cli");
  const std::string dsm = write_dsm(dir);
  const test::RunResult r = test::run_skyview("horizon " + dsm + " " + dir + "/h.tif --directions 4 --preview " + dir +
                                                  "/p.png --preview-band horizon_azimuth_90",
                                              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const test::PreviewPicture p = test::read_preview(dir + "/p.png");
  EXPECT_EQ(p.band, "horizon_azimuth_90");
  EXPECT_EQ(p.title, "horizon_azimuth_90 - h.tif");
  EXPECT_EQ(p.ramp, "cividis");
  expect_preview_shows(dir + "/p.png", dir + "/h.tif", 2, ColourRamp::cividis);
  // Without --preview-band: the first direction's band.
  ASSERT_EQ(test::run_skyview("horizon " + dsm + " " + dir + "/h2.tif --directions 4 --preview " + dir + "/p2.png", dir)
                .exit_code,
            0);
  EXPECT_EQ(test::read_preview(dir + "/p2.png").band, "horizon_azimuth_0");
  expect_preview_shows(dir + "/p2.png", dir + "/h2.tif", 1, ColourRamp::cividis);
}

TEST(PreviewCli, DsmDrawsHeightsInMagma) {
  const std::string dir = test::temp_dir("preview-cli");
  const std::string dsm = write_dsm(dir);
  const test::RunResult r =
      test::run_skyview("dsm " + dir + "/out.tif --dem " + dsm + " --preview " + dir + "/p.png", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const test::PreviewPicture p = test::read_preview(dir + "/p.png");
  EXPECT_EQ(p.band, "height");
  EXPECT_EQ(p.ramp, "magma");
  expect_preview_shows(dir + "/p.png", dir + "/out.tif", 1, ColourRamp::magma);
}

TEST(PreviewCli, BadRangeOrBandIsUsageOnEveryCommand) {
  const std::string dir = test::temp_dir("preview-cli");
  const std::string dsm = write_dsm(dir), png = " --preview " + dir + "/p.png";
  const std::string day = " --from 2024-06-21T00:00Z --to 2024-06-22T00:00Z --step 1h";
  const std::vector<std::string> commands{
      "svf " + dsm + " " + dir + "/o.tif",
      "horizon " + dsm + " " + dir + "/o.tif",
      "dsm " + dir + "/o.tif --dem " + dsm,
      "exposure " + dsm + " " + dir + "/o.tif --map-size 32" + day,
      "shadow " + dsm + " " + dir + "/o.tif --time 2024-06-21T12:00Z",
      "sunhours " + dsm + " " + dir + "/o.tif" + day,
      "skymap " + dir + "/o.tif --lat 57.7 --lon 15 --size 32" + day,
  };
  for (const std::string& c : commands) {
    SCOPED_TRACE(c);
    test::expect_one_line_error(test::run_skyview(c + png + " --preview-range 1,0", dir), "--preview-range", 2);
    test::expect_one_line_error(test::run_skyview(c + png + " --preview-range a,b", dir), "MIN,MAX", 2);
    const test::RunResult band = test::run_skyview(c + png + " --preview-band nosuch", dir);
    test::expect_one_line_error(band, "--preview-band 'nosuch' is not a band of the output; it holds ", 2);
    EXPECT_FALSE(std::filesystem::exists(dir + "/o.tif"));
    EXPECT_FALSE(std::filesystem::exists(dir + "/p.png"));
  }
  // The bands are named as written.
  const test::RunResult svf =
      test::run_skyview(commands[0] + " --products svf,sky_visibility" + png + " --preview-band svf_surface", dir);
  test::expect_one_line_error(svf, "it holds svf, sky_visibility", 2);
  // Without --preview the other two have nothing to do.
  test::expect_one_line_error(test::run_skyview(commands[0] + " --preview-range 0,1", dir),
                              "--preview-range applies only to runs with --preview", 2);
}

TEST(PreviewCli, ExposureShadowSunhoursSkymapEndWithOneSummaryLine) {
  const std::string dir = test::temp_dir("preview-cli");
  const std::string dsm = write_dsm(dir);
  const std::string day = " --from 2024-06-21T00:00Z --to 2024-06-22T00:00Z --step 1h";
  const std::vector<std::pair<std::string, std::string>> runs{
      {"exposure", "exposure " + dsm + " " + dir + "/e.tif --map-size 32" + day},
      {"shadow", "shadow " + dsm + " " + dir + "/s.tif --time 2024-06-21T12:00Z"},
      {"sunhours", "sunhours " + dsm + " " + dir + "/h.tif" + day},
      {"skymap", "skymap " + dir + "/m.tif --no-preview --lat 57.7 --lon 15 --size 32" + day},
  };
  for (const auto& [name, args] : runs) {
    int code = -1;
    const std::string err = run_loud(args, dir, code);
    EXPECT_EQ(code, 0) << err;
    // The last line is RunSummary's: "skyview NAME: ...; S s, peak M GB".
    const std::size_t start = err.rfind('\n', err.size() >= 2 ? err.size() - 2 : 0);
    const std::string last = err.substr(start == std::string::npos ? 0 : start + 1);
    SCOPED_TRACE(err);
    EXPECT_EQ(last.rfind("skyview " + name + ": ", 0), 0u);
    EXPECT_NE(last.find(" s, peak "), std::string::npos);
    EXPECT_NE(last.find(" GB\n"), std::string::npos);
    // One summary: no second line of the command's own.
    EXPECT_EQ(err.find("skyview " + name + ": "), start == std::string::npos ? 0 : start + 1);
  }
}

// A footprint layer of `n` squares over the DSM, with no attribute at all (no height field).
std::string write_footprints(const std::string& dir, int n, bool bow_tie = false) {
  init_gdal();
  const std::string path = dir + "/fp.gpkg";
  GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GPKG");
  GDALDatasetUniquePtr ds(drv->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  OGRSpatialReference crs;
  crs.importFromEPSG(32633);
  crs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRLayer* layer = ds->CreateLayer("buildings", &crs, wkbPolygon, nullptr);
  if (bow_tie) layer->CreateField(std::make_unique<OGRFieldDefn>("h", OFTReal).get());
  for (int i = 0; i < n; ++i) {
    const double x = 500004.0 + 12.0 * i, y = 6399996.0;
    char wkt[256];
    if (bow_tie && i == 0)  // crosses itself: GEOS says so while checking it
      std::snprintf(wkt, sizeof wkt, "POLYGON((%f %f,%f %f,%f %f,%f %f,%f %f))", x, y, x + 8, y - 8, x + 8, y, x, y - 8,
                    x, y);
    else
      std::snprintf(wkt, sizeof wkt, "POLYGON((%f %f,%f %f,%f %f,%f %f,%f %f))", x, y, x + 8, y, x + 8, y - 8, x, y - 8,
                    x, y);
    OGRGeometry* g = nullptr;
    OGRGeometryFactory::createFromWkt(wkt, &crs, &g);
    OGRFeature f(layer->GetLayerDefn());
    f.SetGeometryDirectly(g);
    if (bow_tie) f.SetField("h", 10.0);
    EXPECT_EQ(layer->CreateFeature(&f), OGRERR_NONE);
  }
  return path;
}

TEST(DsmCli, FootprintsOfWhichNoneBurnAreAnError) {
  const std::string dir = test::temp_dir("preview-cli");
  const std::string dsm = write_dsm(dir), fp = write_footprints(dir, 3);
  const test::RunResult r = test::run_skyview("dsm " + dir + "/o.tif --dem " + dsm + " --footprints " + fp, dir);
  test::expect_one_line_error(
      r, "none of the 3 footprints of '" + fp + "' was burned (all skipped): they have no height", 1);
  EXPECT_NE(r.err.find("--height-field"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir + "/o.tif"));
  const test::RunResult allowed =
      test::run_skyview("dsm " + dir + "/o.tif --dem " + dsm + " --footprints " + fp + " --allow-unburned", dir);
  EXPECT_EQ(allowed.exit_code, 0) << allowed.err;
  EXPECT_TRUE(std::filesystem::exists(dir + "/o.tif"));
}

TEST(DsmCli, GeosMessagesAreOursOrSilent) {
  const std::string dir = test::temp_dir("preview-cli");
  const std::string dsm = write_dsm(dir), fp = write_footprints(dir, 2, true);
  int code = -1;
  const std::string err =
      run_loud("dsm " + dir + "/o.tif --dem " + dsm + " --footprints " + fp + " --height-field h", dir, code);
  EXPECT_EQ(code, 0) << err;
  // Every line is skyview's: a warning or the summary, none of GEOS's own; GEOS's notes are said once.
  int geos_lines = 0;
  std::size_t start = 0;
  while (start < err.size()) {
    const std::size_t end = err.find('\n', start);
    const std::string line = err.substr(start, end - start);
    EXPECT_TRUE(line.rfind("Warning: ", 0) == 0 || line.rfind("skyview dsm: ", 0) == 0) << line;
    EXPECT_NE(line.rfind("Warning: Self-intersection", 0), 0u) << line;
    if (line.find("GEOS") != std::string::npos) {
      ++geos_lines;
      EXPECT_EQ(line.rfind("Warning: 1 note from GEOS while checking the footprints of '" + fp + "' (the first: ", 0),
                0u)
          << line;
    }
    if (end == std::string::npos) break;
    start = end + 1;
  }
  EXPECT_EQ(geos_lines, 1) << err;
}

}  // namespace
}  // namespace skyview
