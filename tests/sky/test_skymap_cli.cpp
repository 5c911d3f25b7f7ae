// `skyview skymap` from the command line: a small run writes both bands and the preview; bad
// input gives one error line and a non-zero exit.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include "sky_test_support.h"

namespace {

struct Result {
  int code;
  std::string output;
};

Result run(const std::string& args) {
  const std::string cmd = std::string(SKYVIEW_EXE) + " skymap " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  std::array<char, 512> buf;
  while (pipe && fgets(buf.data(), buf.size(), pipe)) out += buf.data();
  const int status = pipe ? pclose(pipe) : -1;
  return {WEXITSTATUS(status), out};
}

TEST(SkymapCli, WritesBandsAndPreview) {
  const auto dir = std::filesystem::temp_directory_path() / "skyview_skymap_cli";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string out = (dir / "map.tif").string();
  const Result r = run(out + " --lat 45 --lon 7 --from 2024-06-21T00:00Z --to 2024-06-22T00:00Z --size 64 -q");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(out));
  EXPECT_TRUE(std::filesystem::exists(dir / "map.png"));
  EXPECT_EQ(run("--help").code, 0);
  std::filesystem::remove_all(dir);
}

TEST(SkymapCli, BadInputIsOneErrorLine) {
  for (const char* args :
       {"x.tif --lat 95 --lon 0 --from 2024-01-01T00:00Z --to 2024-01-02T00:00Z", "x.tif --sky perez-epw",
        "x.tif --lat 1 --lon 1 --from 2024-01-02T00:00Z --to 2024-01-01T00:00Z",
        "x.tif --lat 1 --lon 1 --sky sunny --from 2024-01-01T00:00Z --to 2024-01-02T00:00Z",
        "x.tif --sky perez-epw --epw /nonexistent.epw"}) {
    const Result r = run(std::string("--no-preview ") + args);
    EXPECT_NE(r.code, 0) << args;
    EXPECT_EQ(r.output.find("error:"), r.output.rfind("error:")) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
}

}  // namespace
