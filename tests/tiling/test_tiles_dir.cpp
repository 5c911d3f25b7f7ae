// --tiles-dir: one GeoTIFF per tile and a VRT mosaic with the same bits as a single run, a manifest
// that lets a rerun skip finished tiles and redo lost or damaged ones, and refusals that name what
// is wrong.
#include <filesystem>
#include <fstream>

#include "tiling/tiling_test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

int tiles_in(const std::string& dir) {
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    n += entry.path().filename().string().rfind("tile_", 0) == 0 && entry.path().extension() == ".tif";
  return n;
}

TEST(TilesDir, MosaicEqualsASingleRunAndARerunRedoesOnlyLostTiles) {
  const std::string dir = temp_dir("tiles-dir");
  const std::string dsm = write_small_city(dir);
  const std::string common = " --radius 9 --directions 16";
  ASSERT_EQ(run_skyview("svf " + dsm + " " + dir + "/whole.tif" + common, dir).exit_code, 0);
  const std::string tiles = dir + "/tiles", vrt = dir + "/mosaic.vrt";
  const std::string run = "svf " + dsm + " " + vrt + common + " --tile-size 22 --tiles-dir " + tiles;
  RunResult r = run_skyview(run, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(tiles_in(tiles), 12);  // 4 x 3 tiles, the last column one cell wide
  EXPECT_TRUE(std::filesystem::exists(tiles + "/manifest.json"));
  EXPECT_TRUE(same_bands(vrt, dir + "/whole.tif"));
  EXPECT_EQ(metadata_item(vrt, "EDGE_CELLS"), metadata_item(dir + "/whole.tif", "EDGE_CELLS"));
  EXPECT_EQ(metadata_item(vrt, "SOURCE"), dsm);

  // A lost tile, a damaged one and no mosaic (a run killed before its end): the rerun makes those
  // two again and keeps the other ten as they are.
  const auto kept_time = std::filesystem::last_write_time(tiles + "/tile_0_0.tif");
  std::filesystem::remove(tiles + "/tile_1_1.tif");
  {
    std::fstream damaged(tiles + "/tile_2_3.tif", std::ios::in | std::ios::out | std::ios::binary);
    damaged.seekp(300);
    damaged.write("damage", 6);
  }
  std::filesystem::remove(vrt);
  r = run_skyview(run, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(tiles_in(tiles), 12);
  EXPECT_EQ(metadata_item(vrt, "TILES_REUSED"), "10");
  EXPECT_EQ(std::filesystem::last_write_time(tiles + "/tile_0_0.tif"), kept_time);
  EXPECT_TRUE(same_bands(vrt, dir + "/whole.tif"));
}

TEST(TilesDir, RefusesAnotherRunsTilesUnlessOverwrite) {
  const std::string dir = temp_dir("tiles-dir-other");
  const std::string dsm = write_small_city(dir);
  const std::string tiles = dir + "/tiles";
  ASSERT_EQ(
      run_skyview("horizon " + dsm + " " + dir + "/a.vrt --radius 9 --directions 4 --tile-size 30 --tiles-dir " + tiles,
                  dir)
          .exit_code,
      0);
  const std::string other =
      "horizon " + dsm + " " + dir + "/b.vrt --radius 7 --directions 4 --tile-size 30 --tiles-dir " + tiles;
  expect_one_line_error(run_skyview(other, dir), "holds the tiles of another run");
  EXPECT_FALSE(std::filesystem::exists(dir + "/b.vrt"));
  ASSERT_EQ(run_skyview(other + " --overwrite", dir).exit_code, 0);
  ASSERT_EQ(run_skyview("horizon " + dsm + " " + dir + "/b.tif --radius 7 --directions 4", dir).exit_code, 0);
  EXPECT_TRUE(same_bands(dir + "/b.vrt", dir + "/b.tif"));
}

TEST(TilesDir, BadOutputsAndUnwritableTilesAreOneLineErrors) {
  const std::string dir = temp_dir("tiles-dir-bad");
  const std::string dsm = write_small_city(dir);
  expect_one_line_error(
      run_skyview("svf " + dsm + " " + dir + "/out.tif --radius 9 --tile-size 30 --tiles-dir " + dir + "/t", dir),
      "the output of --tiles-dir", 2);
  // Files that cannot grow (as on a full disk): the error names the tile.
  const RunResult r =
      run_skyview("svf " + dsm + " " + dir + "/out.vrt --radius 9 --tile-size 30 --tiles-dir " + dir + "/t", dir, 1500);
  expect_one_line_error(r, "tile_0_0.tif");
  EXPECT_FALSE(std::filesystem::exists(dir + "/out.vrt"));
}

}  // namespace
