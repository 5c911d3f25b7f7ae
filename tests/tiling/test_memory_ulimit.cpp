// A tiled run stays within the address space `ulimit -v` allows where the whole run does not fit.
#include <cstdlib>

#include "tiling/tiling_test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

TEST(MemoryLimit, TiledRunSucceedsUnderUlimitWhereTheWholeRunRunsOutOfMemory) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space for its shadow, which ulimit -v forbids";
#endif
  if (std::system("sh -c 'ulimit -v 4000000' >/dev/null 2>&1") != 0) GTEST_SKIP() << "this shell cannot set ulimit -v";
  const std::string dir = temp_dir("memory-ulimit");
  // 9 million cells: the whole run holds about 0.32 GB resident besides the program's 0.23 GB of
  // address space.
  ASSERT_EQ(run_skyview("synth city " + dir + "/city.tif --size 3000 --cell 1 --crs EPSG:32633", dir).exit_code, 0);
  const std::string limited = "ulimit -v 380000 && exec " + std::string(SKYVIEW_EXE);
  const std::string common = " --radius 20 --directions 8 --products svf --threads 1";
  // --memory-limit 4G: the run's estimate fits that, so it goes whole, and the address space runs out.
  expect_one_line_error(
      run_executable(limited, "svf " + dir + "/city.tif " + dir + "/whole.tif" + common + " --memory-limit 4G", dir),
      "out of memory", 1);
  const RunResult r =
      run_executable(limited, "svf " + dir + "/city.tif " + dir + "/tiled.tif" + common + " --memory-limit 250M", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(std::stoi(metadata_item(dir + "/tiled.tif", "TILES")), 1);
  EXPECT_LT(std::stoull(metadata_item(dir + "/tiled.tif", "PEAK_MEMORY_BYTES")), 380000ull * 1024);
  // The same bits as a whole run without the limit.
  ASSERT_EQ(run_skyview("svf " + dir + "/city.tif " + dir + "/free.tif" + common, dir).exit_code, 0);
  EXPECT_TRUE(same_bands(dir + "/tiled.tif", dir + "/free.tif"));
}

}  // namespace
