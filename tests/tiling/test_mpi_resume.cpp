// An mpirun whose rank is killed mid-run leaves its finished tiles recorded, and a rerun completes
// them with the same bits as one process.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <thread>

#include "tiling/tiling_test_support.h"

using namespace skyview;
using namespace skyview::test;

namespace {

int tiles_in(const std::string& dir) {
  int n = 0;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("tile_", 0) == 0 && e.path().extension() == ".tif") ++n;
  }
  return n;
}

// The child of `parent` whose environment says it is MPI rank `rank`; 0 if none.
pid_t rank_process(pid_t parent, int rank) {
  const std::string want = "OMPI_COMM_WORLD_RANK=" + std::to_string(rank);
  for (const auto& e : std::filesystem::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::ifstream stat(e.path() / "stat");
    std::string pid, comm, state;
    pid_t ppid = 0;
    if (!(stat >> pid >> comm >> state >> ppid) || ppid != parent) continue;
    std::ifstream env(e.path() / "environ");
    for (std::string var; std::getline(env, var, '\0');)
      if (var == want) return static_cast<pid_t>(std::stol(name));
  }
  return 0;
}

TEST(MpiTiles, ARankKilledMidRunThenARerunGiveTheSameBitsAsOneProcess) {
  if (std::system("command -v mpirun >/dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun is not installed";
  const std::string dir = temp_dir("mpi-resume");
  const std::string dsm = write_small_city(dir, 240, 200);
  const std::string common = " --radius 30 --directions 32 --tile-size 16";
  ASSERT_EQ(run_skyview("svf " + dsm + " " + dir + "/one.vrt" + common + " --tiles-dir " + dir + "/one", dir).exit_code,
            0);
  const std::string mpirun = mpirun_two_ranks();
  const std::string args = "svf " + dsm + " " + dir + "/two.vrt" + common + " --tiles-dir " + dir + "/two -q";
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string cmd = "exec " + mpirun + " " + args + " 2>" + dir + "/killed.txt >/dev/null";
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // Some tiles written (of 15 x 13), then the computing rank killed.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::minutes(5);
  pid_t worker = 0;
  while (std::chrono::steady_clock::now() < give_up) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) {
      std::ifstream in(dir + "/killed.txt");
      const std::string err((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      if (err.find("built without MPI") != std::string::npos) GTEST_SKIP() << "this build has no MPI";
      FAIL() << "the run ended before it could be killed: " << err;
    }
    if (tiles_in(dir + "/two") >= 5 && (worker = rank_process(pid, 1)) != 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_NE(worker, 0) << "no rank 1 found under mpirun " << pid;
  ASSERT_EQ(kill(worker, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  EXPECT_FALSE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "mpirun succeeded with a rank killed";
  const int done = tiles_in(dir + "/two");
  ASSERT_LT(done, 15 * 13) << "every tile was finished before the kill";
  EXPECT_FALSE(std::filesystem::exists(dir + "/two.vrt"));  // no mosaic of a part
  // The rerun keeps the finished tiles and makes the rest.
  const RunResult r = run_executable(mpirun, args, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(same_bands(dir + "/two.vrt", dir + "/one.vrt"));
  const std::string reused = metadata_item(dir + "/two.vrt", "TILES_REUSED");
  ASSERT_FALSE(reused.empty());
  EXPECT_GT(std::stoi(reused), 0);
  EXPECT_LT(std::stoi(reused), 15 * 13);
}

}  // namespace

namespace {

// Rank 0 builds the far field's pyramid and sends it to the other rank (which never reads the
// raster whole): the same bits, the same pyramid file as one process; a rerun reads it back.
TEST(MpiTiles, FarFieldRunsGiveTheSameBitsAsOneProcess) {
  if (std::system("command -v mpirun >/dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun is not installed";
  const std::string dir = temp_dir("mpi-far-field");
  const std::string dsm = write_small_city(dir, 240, 200);  // a far field beyond 183 m
  const std::string options = " --directions 8 --tile-size 64 --far-field-error 0.3";
  const RunResult r = svf_once_and_under_mpirun(dsm, options, dir);
  if (r.exit_code != 0 && r.err.find("built without MPI") != std::string::npos)
    GTEST_SKIP() << "this build has no MPI: " << r.err;
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(same_bands(dir + "/two.vrt", dir + "/one.vrt"));
  EXPECT_LT(std::stod(metadata_item(dir + "/two.vrt", "FAR_FIELD_HALO_M")), 300.0);
  auto bytes_of = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  const std::string pyramid = bytes_of(dir + "/two/far_field_pyramid.bin");
  EXPECT_GT(pyramid.size(), 1000u);
  EXPECT_EQ(bytes_of(dir + "/one/far_field_pyramid.bin"), pyramid);
  const std::vector<int> by_rank = tiles_by_rank(dir + "/two.vrt");
  ASSERT_EQ(by_rank.size(), 2u);
  EXPECT_GT(by_rank[0], 0);  // rank 0 computed tiles too
  EXPECT_EQ(by_rank[0] + by_rank[1], 16);

  // The rerun of a run that lost a tile and its mosaic reads the pyramid kept in the folder.
  std::filesystem::remove(dir + "/two/tile_0_0.tif");
  std::filesystem::remove(dir + "/two.vrt");
  const RunResult again = run_executable(
      mpirun_two_ranks(), "svf " + dsm + " " + dir + "/two.vrt" + options + " --tiles-dir " + dir + "/two", dir);
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(metadata_item(dir + "/two.vrt", "FAR_FIELD_PYRAMID_REUSED"), dir + "/two/far_field_pyramid.bin");
  EXPECT_EQ(metadata_item(dir + "/two.vrt", "TILES_REUSED"), "15");
  EXPECT_EQ(bytes_of(dir + "/two/far_field_pyramid.bin"), pyramid);
  EXPECT_TRUE(same_bands(dir + "/two.vrt", dir + "/one.vrt"));
}

}  // namespace
