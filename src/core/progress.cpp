#include "skyview/core/progress.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace skyview {

double ProgressCounter::fraction() const {
  return std::min(1.0, static_cast<double>(done_.load(std::memory_order_relaxed)) / total_.load());
}

ProgressReporter::ProgressReporter(const ProgressCounter& counter, bool quiet) : counter_(counter), quiet_(quiet) {
  if (quiet_) return;
  print_up_to(0.0);
  thread_ = std::thread([this] {
    while (!stop_.load()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      print_up_to(counter_.fraction());
    }
  });
}

ProgressReporter::~ProgressReporter() {
  if (quiet_) return;
  stop_.store(true);
  thread_.join();
  print_up_to(1.0);
  std::fputs(" - done.\n", stderr);
  std::fflush(stderr);
}

void ProgressReporter::print_up_to(double fraction) {
  // GDAL's pattern: a number every 10 %, a dot every 2.5 % in between.
  const int tick = static_cast<int>(fraction * 40.0 + 1e-9);
  while (printed_ < tick) {
    ++printed_;
    if (printed_ % 4 == 0) {
      std::fprintf(stderr, "%d", printed_ * 10 / 4);
    } else {
      std::fputc('.', stderr);
    }
  }
  std::fflush(stderr);
}

}  // namespace skyview
