// Rasters whose cells and heights cannot both be metres are refused with the option that states
// the unit; a raster that states no CRS or no geotransform is said on stderr (issue 32: an ASCII
// grid in degrees without its .prj ran silently and gave a mean svf of 0.12 where its CRS gives 0.72).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "cli_run.h"
#include "skyview/core/error.h"
#include "skyview/raster/raster_io.h"
#include "test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

// An Arc/Info ASCII grid of a 40 m deep pit, in cells of `cell` at (x0, y0), without a .prj.
std::string write_ascii_pit(const std::string& path, double x0, double y0, double cell) {
  std::ofstream out(path);
  const int n = 21;
  out << "ncols " << n << "\nnrows " << n << "\nxllcorner " << x0 << "\nyllcorner " << y0 << "\ncellsize " << cell
      << "\nNODATA_value -9999\n";
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) out << ((std::abs(r - 10) < 4 && std::abs(c - 10) < 4) ? 100 : 140) << " ";
    out << "\n";
  }
  return path;
}

HeightValues pit_values(double cell, const std::string& crs) {
  HeightValues h;
  h.name = "array";
  h.width = h.height = 21;
  for (int r = 0; r < 21; ++r)
    for (int c = 0; c < 21; ++c) h.values.push_back((std::abs(r - 10) < 4 && std::abs(c - 10) < 4) ? 100 : 140);
  h.georef.has_geotransform = true;
  h.georef.geotransform = {500000, cell, 0, 4983000, 0, -cell};
  h.georef.crs_wkt = crs;
  return h;
}

}  // namespace

TEST(UnitsAndCrs, AGridInDegreesWithoutItsCrsIsRefusedAndRunsWithSSrs) {
  const std::string dir = temp_dir("units");
  // 3 arc-seconds (about 90 m) in Athens: 40 m of relief over 1.4 km.
  const std::string grid = write_ascii_pit(dir + "/pit.asc", 23.7, 37.9, 1.0 / 1200);
  expect_one_line_error(run_skyview("svf " + grid + " " + dir + "/s.tif", dir), "look like degrees");
  const RunResult r = run_skyview("svf " + grid + " " + dir + "/s.tif --s_srs EPSG:4326 --products svf", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("Warning"), std::string::npos) << r.err;
  // With its CRS the 630 m pit floor of 90 m cells sees most of the sky (40 m deep, 270 m from the
  // rim at least): svf well above 0.9 at the floor's centre.
  const RasterBand svf = read_band(dir + "/s.tif", 1);
  EXPECT_GT(svf.values(10, 10), 0.9f);
  EXPECT_NE(read_band(dir + "/s.tif", 1).georef.crs_wkt.find("WGS"), std::string::npos);
}

TEST(UnitsAndCrs, ARasterWithoutACrsIsSaidOnStderr) {
  const std::string dir = temp_dir("units");
  const std::string grid = write_ascii_pit(dir + "/pit.asc", 1000, 2000, 1.0);
  const RunResult r = run_skyview("svf " + grid + " " + dir + "/s.tif --products svf -q", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("has no CRS: its coordinates are taken as metres"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST(UnitsAndCrs, CellsOfMillimetresAgainstMetresOfReliefAreRefused) {
  // 1 mm cells against 40 m of relief: heights in millimetres, or cells in some other unit.
  HeightValues h = pit_values(0.001, wkt_of("EPSG:32633"));
  h.height_unit = "metres (assumed: the CRS is in metres, no height unit stated)";
  try {
    terrain_from_heights(std::move(h), {});
    FAIL() << "not refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot both be metres"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--z-scale"), std::string::npos) << e.what();
  }
  // Stated heights on a stated CRS are taken as they are (a 2 cm façade scan can be 40 m tall).
  HeightValues stated = pit_values(0.001, wkt_of("EPSG:32633"));
  stated.height_unit = "--z-scale";
  const Terrain t = terrain_from_heights(std::move(stated), {});
  EXPECT_NEAR(raster_centre_jacobian(t).min_cell_size(), 0.001, 1e-5);
}

TEST(UnitsAndCrs, HeightsFromMemoryGoThroughTheSameChecksAsFiles) {
  HeightValues h = pit_values(10.0, wkt_of("EPSG:32633"));
  h.values[0] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(terrain_from_heights(std::move(h), {}), Error);
  HeightValues ok = pit_values(10.0, wkt_of("EPSG:32633"));
  ok.values[5] = -9999;
  ok.has_nodata = true;
  ok.nodata = -9999;
  ReadReport report;
  const Terrain t = terrain_from_heights(std::move(ok), {}, &report);
  EXPECT_EQ(report.nodata_cells, 1);
  EXPECT_TRUE(std::isnan(t.heights(5, 0)));
  EXPECT_NEAR(t.absolute_height(10, 10), 100.0, 1e-4);
}

TEST(UnitsAndCrs, AnUnknownSSrsIsRefused) {
  const std::string dir = temp_dir("units");
  const std::string grid = write_ascii_pit(dir + "/pit.asc", 1000, 2000, 1.0);
  expect_one_line_error(run_skyview("svf " + grid + " " + dir + "/s.tif --s_srs EPSG:999999", dir),
                        "is not a CRS GDAL knows");
}
