#pragma once
// How many oneTBB workers the library's parallel loops may use, for as long as a ThreadLimit lives:
// the command line's --threads and the Python functions' threads= share it.
#include <memory>

namespace skyview {

class ThreadLimit {
 public:
  // 0: all cores. Throws UsageError for a negative count.
  explicit ThreadLimit(int threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

 private:
  std::shared_ptr<void> control_;
};

}  // namespace skyview
