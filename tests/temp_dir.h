#pragma once
// Scratch folders for tests: one per test and process (ctest runs tests in parallel, and two test
// runs may share /tmp), removed when the test ends unless it failed, when it is kept for a look.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace skyview::test {

// Removes the folders the ending test made, or names them on stderr if it failed.
class TempDirCleaner : public ::testing::EmptyTestEventListener {
 public:
  static std::vector<std::string>& made() {
    static std::vector<std::string> dirs;
    return dirs;
  }
  void OnTestEnd(const ::testing::TestInfo& info) override {
    for (const std::string& dir : made()) {
      if (info.result()->Failed()) {
        std::fprintf(stderr, "kept %s (the test failed)\n", dir.c_str());
      } else {
        std::error_code ignored;
        std::filesystem::remove_all(dir, ignored);
      }
    }
    made().clear();
  }
};

// Installed once per test binary, before any test runs (gtest owns the listener).
inline const bool kTempDirCleanerInstalled = [] {
  ::testing::UnitTest::GetInstance()->listeners().Append(new TempDirCleaner);
  return true;
}();

// A fresh, empty folder named after the running test, `name` and the process.
inline std::string temp_dir(const std::string& name) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string test = info ? std::string(info->test_suite_name()) + "." + info->name() : "none";
  for (char& ch : test) {
    if (ch == '/') ch = '_';
  }
  const auto dir =
      std::filesystem::temp_directory_path() / ("skyview-test-" + name + "-" + test + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  TempDirCleaner::made().push_back(dir.string());
  return dir.string();
}

}  // namespace skyview::test
