#pragma once
// What the documentation tests share: the repository's files, and the skyview executable's output.
#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace skyview::test {

// The text of the file at `path`; empty when absent.
inline std::string file_text(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The text of `relative` under the source tree ("docs/commands/svf.md"); empty when absent.
inline std::string source_file_text(const std::string& relative) {
  return file_text(std::string(SKYVIEW_SOURCE_DIR) + "/" + relative);
}

// Standard output of `skyview ARGS` (stderr discarded).
inline std::string skyview_output(const std::string& args) {
  const std::string cmd = std::string(SKYVIEW_EXE) + " " + args + " 2>/dev/null";
  std::FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  char buffer[4096];
  for (std::size_t n; pipe && (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) out.append(buffer, n);
  if (pipe) pclose(pipe);
  return out;
}

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

}  // namespace skyview::test
