#include "skyview/core/thread_limit.h"

#include <tbb/global_control.h>

#include "skyview/core/error.h"

namespace skyview {

ThreadLimit::ThreadLimit(int threads) {
  if (threads < 0) throw UsageError("threads must be 0 (all cores) or more");
  if (threads > 0) {
    control_ = std::make_shared<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                     static_cast<std::size_t>(threads));
  }
}

ThreadLimit::~ThreadLimit() = default;

}  // namespace skyview
