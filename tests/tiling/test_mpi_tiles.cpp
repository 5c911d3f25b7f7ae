// Ranks of an mpirun share a --tiles-dir run's tiles and give the same bits as one process.
#include <cstdlib>
#include <filesystem>

#include "tiling/tiling_test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

TEST(MpiTiles, TwoRanksGiveTheSameBitsAsOneProcess) {
  if (std::system("command -v mpirun >/dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun is not installed";
  const std::string dir = temp_dir("mpi-tiles");
  const std::string dsm = write_small_city(dir);
  const RunResult r = svf_once_and_under_mpirun(dsm, " --radius 9 --directions 8 --tile-size 16", dir);
  if (r.exit_code != 0 && r.err.find("built without MPI") != std::string::npos)
    GTEST_SKIP() << "this build has no MPI: " << r.err;
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(same_bands(dir + "/two.vrt", dir + "/one.vrt"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/two/manifest.json"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/two/tile_3_4.tif"));  // the last of 5 x 4 tiles
  // Rank 0 computed tiles besides handing them out, and both ranks' counts make every tile.
  const std::vector<int> by_rank = tiles_by_rank(dir + "/two.vrt");
  ASSERT_EQ(by_rank.size(), 2u) << metadata_item(dir + "/two.vrt", "TILES_BY_RANK");
  EXPECT_GT(by_rank[0], 0);
  EXPECT_GT(by_rank[1], 0);
  EXPECT_EQ(by_rank[0] + by_rank[1], 20);
  EXPECT_TRUE(tiles_by_rank(dir + "/one.vrt").empty());
}

TEST(MpiTiles, SeveralRanksWithoutTilesDirAreRefused) {
  if (std::system("command -v mpirun >/dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun is not installed";
  const std::string dir = temp_dir("mpi-refused");
  const std::string dsm = write_small_city(dir);
  const RunResult r = run_executable(mpirun_two_ranks(), "svf " + dsm + " " + dir + "/out.tif --radius 9", dir);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_TRUE(r.err.find("give --tiles-dir") != std::string::npos ||
              r.err.find("built without MPI") != std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out.tif"));
}

}  // namespace
