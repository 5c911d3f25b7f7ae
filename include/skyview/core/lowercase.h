#pragma once
// Names matched without regard to case: file extensions, units, format names.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <string_view>

namespace skyview {

inline std::string lowercase(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

// ".tif" for "A/B.TIF"; empty without an extension.
inline std::string lowercase_extension(const std::string& path) {
  return lowercase(std::filesystem::path(path).extension().string());
}

}  // namespace skyview
