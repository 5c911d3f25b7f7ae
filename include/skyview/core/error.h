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

// A failure the caller fixes by changing an option (a value out of range, an option the run would
// not use, two that contradict each other), as opposed to one in the data or the files. Its
// message starts with the option's name. The command line exits 2 for these, as for the options
// it cannot parse, and 1 for the rest; Python raises both as skyview.Error.
class UsageError : public Error {
 public:
  using Error::Error;
};

// Runs `read`, turning a skyview::Error into a UsageError: for reading an option's value with a
// parser that knows nothing of options (a time, a duration).
template <class Read>
auto as_usage_error(Read&& read) -> decltype(read()) {
  try {
    return read();
  } catch (const UsageError&) {
    throw;
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
}

}  // namespace skyview
