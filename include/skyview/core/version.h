#pragma once
#include <string>

namespace skyview {

inline std::string version() { return SKYVIEW_VERSION; }

}  // namespace skyview
