#pragma once
// One exception type for every user-facing failure: its message is the single line a
// command prints before exiting non-zero, so it names the file or option and the problem.
#include <stdexcept>
#include <string>

namespace skyview {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace skyview
