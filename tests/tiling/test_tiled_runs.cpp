// Tiled runs (--tile-size, --memory-limit) give the same bits as whole runs wherever the halo
// holds the radius: several tile sizes, including ones that leave 1-cell-wide remainders and ones
// larger than the raster.
#include "skyview/core/error.h"
#include "skyview/tiling/memory_budget.h"
#include "skyview/tiling/tile_grid.h"
#include "tiling/tiling_test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

TEST(TileGrid, CoversTheRasterOnceWithRemainders) {
  const TileGrid grid(67, 53, 22);
  ASSERT_EQ(grid.tile_cols(), 4);  // 22, 22, 22, 1
  ASSERT_EQ(grid.tile_rows(), 3);  // 22, 22, 9
  std::vector<int> hits(67 * 53, 0);
  for (int i = 0; i < grid.count(); ++i) {
    const Window w = grid.core(i);
    for (int r = w.row0; r < w.row0 + w.rows; ++r)
      for (int c = w.col0; c < w.col0 + w.cols; ++c) ++hits[static_cast<std::size_t>(r) * 67 + c];
  }
  EXPECT_TRUE(std::all_of(hits.begin(), hits.end(), [](int h) { return h == 1; }));
  EXPECT_EQ(grid.core(3).cols, 1);
  EXPECT_EQ(grid.core(11).rows, 9);
  const Window read = with_halo(grid.core(5), 10, 67, 53);  // the second row's second tile
  EXPECT_EQ(read.col0, 12);
  EXPECT_EQ(read.row0, 12);
  EXPECT_EQ(read.cols, 42);
  EXPECT_EQ(read.rows, 41);  // clipped at the last row
  const Window in = inside(grid.core(5), read);
  EXPECT_EQ(in.col0, 10);
  EXPECT_EQ(in.row0, 10);
  const Window edge = with_halo(grid.core(0), 10, 67, 53);  // clipped at the raster's corner
  EXPECT_EQ(edge.col0, 0);
  EXPECT_EQ(edge.cols, 32);
  EXPECT_THROW(TileGrid(10, 10, 0), UsageError);
}

TEST(MemoryBudget, ParsesSizes) {
  EXPECT_EQ(parse_memory_size("8G"), 8ull << 30);
  EXPECT_EQ(parse_memory_size("512M"), 512ull << 20);
  EXPECT_EQ(parse_memory_size("512MB"), 512ull << 20);
  EXPECT_EQ(parse_memory_size("1.5GiB"), 3ull << 29);
  EXPECT_EQ(parse_memory_size("4096"), 4096u);
  for (const char* bad : {"12Q", "", "G", "-1G", "0", "8 G", "nan", "inf"}) {
    EXPECT_THROW(parse_memory_size(bad), UsageError) << bad;
  }
  EXPECT_GT(available_memory_bytes(), 0u);
}

TEST(MemoryBudget, TileSizeFitsTheLimit) {
  MemoryModel m;
  m.per_cell = 100;
  m.fixed = 1000;
  // (limit - fixed) / per_cell = 10^4 cells: a side of 100, less a halo of 10 on each side.
  EXPECT_EQ(tile_size_for(m, 1000 + 100 * 10000, 10, 5000), 80);
  EXPECT_EQ(tile_size_for(m, 1000 + 100 * 10000, 10, 50), 50);              // no larger than the raster
  EXPECT_EQ(tile_size_for(m, 1000 + 100 * 400, 10, 5000), 0);               // not even the halo fits
  EXPECT_EQ(tile_size_for(m, 1000 + 100ull * 1000 * 1000, 10, 5000), 768);  // whole blocks of 256
  EXPECT_LE(m.bytes(100 * 100), 1000 + 100 * 10000u);
}

// Each tile size against the whole run: 7 and 16 divide neither side, 22 leaves a last column of
// one cell, 26 a last row of one, 100 is larger than the raster.
const int kTileSizes[] = {7, 16, 22, 26, 100};

TEST(TiledRuns, SvfAllBandsEqualTheWholeRun) {
  const std::string dir = temp_dir("tiled-svf");
  const std::string dsm = write_small_city(dir);
  const std::string common = " --radius 9 --directions 16";
  ASSERT_EQ(run_skyview("svf " + dsm + " " + dir + "/whole.tif" + common, dir).exit_code, 0);
  ASSERT_EQ(band_count(dir + "/whole.tif"), 5);
  for (int size : kTileSizes) {
    const std::string out = dir + "/tiles" + std::to_string(size) + ".tif";
    const RunResult r = run_skyview("svf " + dsm + " " + out + common + " --tile-size " + std::to_string(size), dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(same_bands(out, dir + "/whole.tif")) << "--tile-size " << size;
    EXPECT_EQ(metadata_item(out, "TILE_SIZE"), std::to_string(size));
    EXPECT_FALSE(metadata_item(out, "PEAK_MEMORY_BYTES").empty());
    EXPECT_EQ(metadata_item(out, "EDGE_CELLS"), metadata_item(dir + "/whole.tif", "EDGE_CELLS"));
  }
}

TEST(TiledRuns, SvfWithEdgeNodataAndTheMarchEqualsTheWholeRun) {
  const std::string dir = temp_dir("tiled-svf-march");
  const std::string dsm = write_small_city(dir);
  const std::string common = " --method march --radius 6 --directions 8 --edge nodata --products svf,openness_negative";
  ASSERT_EQ(run_skyview("svf " + dsm + " " + dir + "/whole.tif" + common, dir).exit_code, 0);
  for (int size : {16, 22}) {
    const std::string out = dir + "/tiles" + std::to_string(size) + ".tif";
    ASSERT_EQ(run_skyview("svf " + dsm + " " + out + common + " --tile-size " + std::to_string(size), dir).exit_code,
              0);
    EXPECT_TRUE(same_bands(out, dir + "/whole.tif")) << "--tile-size " << size;
  }
}

TEST(TiledRuns, HorizonEqualsTheWholeRun) {
  const std::string dir = temp_dir("tiled-horizon");
  const std::string dsm = write_small_city(dir);
  for (const std::string method : {"sweep", "march"}) {
    const std::string common = " --method " + method + " --radius 9 --directions 8";
    const std::string whole = dir + "/whole_" + method + ".tif";
    ASSERT_EQ(run_skyview("horizon " + dsm + " " + whole + common, dir).exit_code, 0);
    ASSERT_EQ(band_count(whole), 8);
    for (int size : method == "sweep" ? std::vector<int>(std::begin(kTileSizes), std::end(kTileSizes))
                                      : std::vector<int>{16, 26}) {
      const std::string out = dir + "/" + method + std::to_string(size) + ".tif";
      const RunResult r =
          run_skyview("horizon " + dsm + " " + out + common + " --tile-size " + std::to_string(size), dir);
      ASSERT_EQ(r.exit_code, 0) << r.err;
      EXPECT_TRUE(same_bands(out, whole)) << method << " --tile-size " << size;
    }
  }
}

TEST(TiledRuns, AMemoryLimitBelowTheWholeRunGoesByTiles) {
  const std::string dir = temp_dir("tiled-limit");
  const std::string dsm = write_small_city(dir);
  const std::string common = " --radius 9 --directions 16";
  ASSERT_EQ(run_skyview("svf " + dsm + " " + dir + "/whole.tif" + common, dir).exit_code, 0);
  EXPECT_TRUE(metadata_item(dir + "/whole.tif", "TILE_SIZE").empty());
  // The program's own allowance and a few thousand cells: tiles smaller than the raster.
  const RunResult r = run_skyview("svf " + dsm + " " + dir + "/limited.tif" + common + " --memory-limit 160.4M", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string size = metadata_item(dir + "/limited.tif", "TILE_SIZE");
  ASSERT_FALSE(size.empty());
  EXPECT_LT(std::stoi(size), 67);
  EXPECT_GT(std::stoi(metadata_item(dir + "/limited.tif", "TILES")), 1);
  EXPECT_TRUE(same_bands(dir + "/limited.tif", dir + "/whole.tif"));
  // A limit that holds not even the program fails, naming the limit.
  expect_one_line_error(run_skyview("svf " + dsm + " " + dir + "/none.tif" + common + " --memory-limit 100M", dir),
                        "--memory-limit 100M holds no tile");
}

TEST(TiledRuns, BadOptionsExitTwo) {
  const std::string dir = temp_dir("tiled-bad");
  const std::string dsm = write_small_city(dir);
  const std::string out = dir + "/out.tif";
  expect_one_line_error(run_skyview("svf " + dsm + " " + out + " --radius 9 --tile-size 0", dir),
                        "--tile-size must be at least 1", 2);
  expect_one_line_error(run_skyview("horizon " + dsm + " " + out + " --radius 9 --tile-size -3", dir),
                        "--tile-size must be at least 1", 2);
  expect_one_line_error(run_skyview("svf " + dsm + " " + out + " --radius 9 --memory-limit 12Q", dir),
                        "--memory-limit '12Q' is not a size", 2);
  expect_one_line_error(run_skyview("svf " + dsm + " " + out + " --radius 9 --tile-size 16 --check-cells 100", dir),
                        "--check-cells is not available", 2);
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
