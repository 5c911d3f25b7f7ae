#pragma once
// Numbers as metadata and messages show them: ten significant digits, no trailing zeros, so that
// 1e-30 does not print as 0.000000 nor 1e30 as thirty-one digits (std::to_string's fixed six
// decimals).
#include <cstdio>
#include <string>

namespace skyview {

inline std::string number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}

}  // namespace skyview
