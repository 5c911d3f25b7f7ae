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
  const std::string common = " --radius 9 --directions 8 --tile-size 16";
  ASSERT_EQ(run_skyview("svf " + dsm + " " + dir + "/one.vrt" + common + " --tiles-dir " + dir + "/one", dir).exit_code,
            0);
  // OpenMPI refuses root without --allow-run-as-root (CI runs as root).
  const RunResult r =
      run_executable("mpirun --allow-run-as-root --oversubscribe -np 2 " + std::string(SKYVIEW_EXE),
                     "svf " + dsm + " " + dir + "/two.vrt" + common + " --tiles-dir " + dir + "/two", dir);
  if (r.exit_code != 0 && r.err.find("built without MPI") != std::string::npos)
    GTEST_SKIP() << "this build has no MPI: " << r.err;
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(same_bands(dir + "/two.vrt", dir + "/one.vrt"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/two/manifest.json"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/two/tile_3_4.tif"));  // the last of 5 x 4 tiles
}

TEST(MpiTiles, SeveralRanksWithoutTilesDirAreRefused) {
  if (std::system("command -v mpirun >/dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun is not installed";
  const std::string dir = temp_dir("mpi-refused");
  const std::string dsm = write_small_city(dir);
  const RunResult r = run_executable("mpirun --allow-run-as-root --oversubscribe -np 2 " + std::string(SKYVIEW_EXE),
                                     "svf " + dsm + " " + dir + "/out.tif --radius 9", dir);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_TRUE(r.err.find("give --tiles-dir") != std::string::npos ||
              r.err.find("built without MPI") != std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out.tif"));
}

}  // namespace
