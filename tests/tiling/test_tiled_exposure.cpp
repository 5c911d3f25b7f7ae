// `skyview exposure` tile by tile (--tile-size, --tiles-dir) gives the same bits as a whole run
// wherever the halo holds the radius. Bit-identity holds, not just closeness: each cell's exposure
// is summed from its own horizons (equal to the whole run's inside the halo), its own Horn normal
// (its neighbours are in the buffer, or the raster's edge is the buffer's) and the one sky map, in
// the same order of directions; the sampled method's per-cell rotation is seeded by the cell's
// place in the whole raster (Terrain::global_id), not in the tile.
#include <filesystem>

#include "skyview/horizon/horizon_engine.h"
#include "skyview/tiling/memory_budget.h"
#include "tiling/tiling_test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

// A clear midsummer day on the small city (at 0° N, 0° E by its CRS): hourly steps, a 64² map.
const std::string kDay = " --from 2024-06-21T00:00Z --to 2024-06-22T00:00Z --step 1h --map-size 64";
const std::string kCommon = " --radius 9 --directions 16" + kDay;

// The run's metadata that tiling must not change.
const char* const kSameKeys[] = {"GLOBAL_HORIZONTAL_UNOBSTRUCTED_KWH_M2",
                                 "EDGE_CELLS",
                                 "ALBEDO",
                                 "ALBEDO_SOURCE",
                                 "SKY_LATITUDE",
                                 "SKY_LONGITUDE",
                                 "RASTER_CENTRE_LAT_LON",
                                 "EXPOSURE_METHOD",
                                 "EXPOSURE_MAP_SIZE",
                                 "PERIOD"};

void expect_same_metadata(const std::string& tiled, const std::string& whole) {
  for (const char* key : kSameKeys) {
    EXPECT_FALSE(metadata_item(whole, key).empty()) << key;
    EXPECT_EQ(metadata_item(tiled, key), metadata_item(whole, key)) << key;
  }
}

// Each tile size against the whole run: 7 and 16 divide neither side (67 x 53), 22 leaves a last
// column of one cell, 26 a last row of one, 100 is larger than the raster.
TEST(TiledExposure, AllBandsEqualTheWholeRun) {
  const std::string dir = temp_dir("tiled-exposure");
  const std::string dsm = write_small_city(dir);
  const RunResult whole = run_skyview("exposure " + dsm + " " + dir + "/whole.tif" + kCommon, dir);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  ASSERT_EQ(band_count(dir + "/whole.tif"), 6);
  ASSERT_GT(std::stod(metadata_item(dir + "/whole.tif", "GLOBAL_HORIZONTAL_UNOBSTRUCTED_KWH_M2")), 1.0);
  for (int size : {7, 16, 22, 26, 100}) {
    const std::string out = dir + "/tiles" + std::to_string(size) + ".tif";
    const RunResult r =
        run_skyview("exposure " + dsm + " " + out + kCommon + " --tile-size " + std::to_string(size), dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(same_bands(out, dir + "/whole.tif")) << "--tile-size " << size;
    expect_same_metadata(out, dir + "/whole.tif");
    EXPECT_EQ(metadata_item(out, "TILE_SIZE"), std::to_string(size));
    EXPECT_EQ(metadata_item(out, "TILE_HALO_CELLS"), "12");  // ceil(9 m / 0.99 m) + 2 (docs/tiling.md)
  }
}

// The exact method (sun steps against interpolated horizons) and the sampled horizons (a random
// rotation per cell) tile the same way.
TEST(TiledExposure, ExactMethodAndSampledHorizonsEqualTheWholeRun) {
  const std::string dir = temp_dir("tiled-exposure-methods");
  const std::string dsm = write_small_city(dir);
  for (const std::string& how : {std::string(" --method exact"), std::string(" --horizon-method sampled")}) {
    const RunResult whole = run_skyview("exposure " + dsm + " " + dir + "/whole.tif --overwrite" + kCommon + how, dir);
    ASSERT_EQ(whole.exit_code, 0) << whole.err;
    const RunResult r =
        run_skyview("exposure " + dsm + " " + dir + "/tiled.tif --overwrite --tile-size 22" + kCommon + how, dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(same_bands(dir + "/tiled.tif", dir + "/whole.tif")) << how;
    expect_same_metadata(dir + "/tiled.tif", dir + "/whole.tif");
  }
}

// An albedo raster is read a tile's window at a time: its values land on the right cells (a
// gradient across the raster and a nodata patch, so a misplaced window changes reflected light).
TEST(TiledExposure, AlbedoRasterIsReadByWindows) {
  const std::string dir = temp_dir("tiled-exposure-albedo");
  const std::string dsm = write_small_city(dir);
  Terrain albedo = with_local_metric_crs(rasterize(synthetic_city(5), 67, 53, local_grid(67, 53, 1.0)));
  albedo.base_height = 0.0;
  for (int r = 0; r < 53; ++r)
    for (int c = 0; c < 67; ++c) albedo.heights(c, r) = 0.05f + 0.8f * static_cast<float>(c + 2 * r) / 173.0f;
  for (int r = 40; r < 45; ++r) albedo.heights(10, r) = std::numeric_limits<float>::quiet_NaN();
  write_terrain(dir + "/albedo.tif", albedo, {});
  const std::string with = kCommon + " --albedo " + dir + "/albedo.tif";
  const RunResult whole = run_skyview("exposure " + dsm + " " + dir + "/whole.tif" + with, dir);
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  const RunResult r = run_skyview("exposure " + dsm + " " + dir + "/tiled.tif --tile-size 16" + with, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(same_bands(dir + "/tiled.tif", dir + "/whole.tif"));
  EXPECT_EQ(metadata_item(dir + "/tiled.tif", "ALBEDO"), "per cell");
  // Nodata albedo leaves the reflected band without a value there, in both.
  EXPECT_TRUE(std::isnan(read_band(dir + "/tiled.tif", 4).values(10, 42)));
  EXPECT_FALSE(std::isnan(read_band(dir + "/tiled.tif", 4).values(11, 42)));
  // One albedo above 1 in the last tile: refused as the whole run refuses it, and no output.
  albedo.heights(66, 52) = 1.5f;
  WriteOptions again;
  again.overwrite = true;
  write_terrain(dir + "/albedo.tif", albedo, again);
  const RunResult bad = run_skyview("exposure " + dsm + " " + dir + "/bad.tif --tile-size 16" + with, dir);
  expect_one_line_error(bad, "outside 0 .. 1", 2);
  EXPECT_FALSE(std::filesystem::exists(dir + "/bad.tif"));
}

TEST(TiledExposure, TilesDirMosaicEqualsTheWholeRun) {
  const std::string dir = temp_dir("tiled-exposure-dir");
  const std::string dsm = write_small_city(dir);
  ASSERT_EQ(run_skyview("exposure " + dsm + " " + dir + "/whole.tif" + kCommon, dir).exit_code, 0);
  const std::string vrt = dir + "/mosaic.vrt", tiles = dir + "/tiles";
  const RunResult r =
      run_skyview("exposure " + dsm + " " + vrt + kCommon + " --tile-size 22 --tiles-dir " + tiles, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(tiles + "/tile_0_3.tif"));  // the 1-cell-wide last column
  EXPECT_TRUE(std::filesystem::exists(tiles + "/manifest.json"));
  EXPECT_TRUE(same_bands(vrt, dir + "/whole.tif"));
  expect_same_metadata(vrt, dir + "/whole.tif");
  EXPECT_EQ(read_band(vrt, 2).description, "direct");
  EXPECT_EQ(read_band(vrt, 1).unit, "kWh m-2");
}

// The memory model holds at least what svf's does for the same horizons, and the map besides; a
// limit one byte under its estimate of the whole run makes the run go by tiles, with the same bits.
TEST(TiledExposure, MemoryModelAndALimitBelowTheWholeRun) {
  HorizonParams params;
  params.directions = 16;
  params.radius = 9;
  const auto sweep = make_horizon_engine("sweep", params), march = make_horizon_engine("march", params);
  ProductSet svf = ProductSet::none();
  svf.add(Product::svf).add(Product::svf_surface);
  for (const auto* engine : {sweep.get(), march.get()}) {
    const MemoryModel without_map = exposure_memory(*engine, 0), model = exposure_memory(*engine, 64 * 64);
    EXPECT_EQ(model.fixed - without_map.fixed, 256u * 64 * 64);
    EXPECT_GT(model.per_cell, svf_memory(*engine, svf, 6).per_cell - 2 * SkyViewSums::bytes_per_cell(svf));
    EXPECT_GE(model.fixed, svf_memory(*engine, svf, 6).fixed);
  }
  const std::string dir = temp_dir("tiled-exposure-limit");
  const std::string dsm = write_small_city(dir);
  ASSERT_EQ(run_skyview("exposure " + dsm + " " + dir + "/whole.tif" + kCommon, dir).exit_code, 0);
  EXPECT_TRUE(metadata_item(dir + "/whole.tif", "TILE_SIZE").empty());
  EXPECT_FALSE(metadata_item(dir + "/whole.tif", "PEAK_MEMORY_BYTES").empty());
  const std::uint64_t limit = exposure_memory(*sweep, 64 * 64).bytes(67 * 53) - 1;
  const RunResult r = run_skyview(
      "exposure " + dsm + " " + dir + "/limited.tif" + kCommon + " --memory-limit " + std::to_string(limit), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_FALSE(metadata_item(dir + "/limited.tif", "TILE_SIZE").empty());
  EXPECT_GT(std::stoi(metadata_item(dir + "/limited.tif", "TILES")), 1);
  EXPECT_TRUE(same_bands(dir + "/limited.tif", dir + "/whole.tif"));
}

// (Tiles without --radius add the far field: test_far_field_horizon_exposure.cpp.)
TEST(TiledExposure, RefusesAPreviewAndAMosaicThatIsNotAVrt) {
  const std::string dir = temp_dir("tiled-exposure-bad");
  const std::string dsm = write_small_city(dir);
  expect_one_line_error(
      run_skyview("exposure " + dsm + " " + dir + "/b.tif --tile-size 20 --preview " + dir + "/b.png" + kCommon, dir),
      "--preview needs the whole raster", 2);
  expect_one_line_error(
      run_skyview("exposure " + dsm + " " + dir + "/c.tif --tile-size 20 --tiles-dir " + dir + "/t" + kCommon, dir),
      ".vrt", 2);
  for (const char* name : {"/b.tif", "/b.png", "/c.tif"}) EXPECT_FALSE(std::filesystem::exists(dir + name)) << name;
}

}  // namespace
