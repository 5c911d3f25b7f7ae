#pragma once
// Helpers for the sky tests: the shared data folder (skipped when absent) and CSV reading.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace skyview::sky_test {

inline constexpr double kDeg = 3.14159265358979323846 / 180.0;

// Path of a file under ../shared/data, or "" when the shared folder is not there.
inline std::string shared_data(const std::string& relative) {
  const std::filesystem::path p = std::filesystem::path(SKYVIEW_SHARED_DIR) / "data" / relative;
  return std::filesystem::exists(p) ? p.string() : std::string();
}

#define SKYVIEW_REQUIRE_SHARED(var, relative)                         \
  const std::string var = ::skyview::sky_test::shared_data(relative); \
  if (var.empty()) GTEST_SKIP() << "shared data " << (relative) << " not found under " SKYVIEW_SHARED_DIR

// Rows of a CSV file as column-name → text maps.
inline std::vector<std::map<std::string, std::string>> read_csv(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  auto split = [](const std::string& l) {
    std::vector<std::string> out;
    std::stringstream ss(l);
    std::string f;
    while (std::getline(ss, f, ',')) out.push_back(f);
    return out;
  };
  if (std::getline(in, line)) header = split(line);
  while (std::getline(in, line)) {
    const auto f = split(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < f.size(); ++i) row[header[i]] = f[i];
    rows.push_back(row);
  }
  return rows;
}

}  // namespace skyview::sky_test
