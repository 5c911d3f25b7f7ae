#pragma once
// The level of detail city models are read at (SceneLoadOptions::lod): each object's geometries of
// the highest level not above the limit.
#include <limits>
#include <sstream>
#include <string>

#include "skyview/core/error.h"

namespace skyview {

// The limit `lod` states ("2", "2.2"); infinity for an empty one (each object's highest). Throws
// skyview::Error for anything but a number >= 0.
inline double lod_limit(const std::string& lod) {
  if (lod.empty()) return std::numeric_limits<double>::infinity();
  std::size_t used = 0;
  double limit = -1;
  try {
    limit = std::stod(lod, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != lod.size() || !(limit >= 0) || !(limit < std::numeric_limits<double>::infinity())) {
    throw Error("the level of detail must be a number such as 2 or 2.2, not '" + lod + "'");
  }
  return limit;
}

// "2", "2.2": a level as the file and the user write it.
inline std::string lod_text(double lod) {
  std::ostringstream s;
  s << lod;
  return s.str();
}

}  // namespace skyview
