#pragma once
// Progress that many worker threads advance and exactly one thread reports.
// GDALTermProgress writes to stdout and is not thread-safe, so the reporter here prints
// GDAL's "0...10...20..." pattern itself, to stderr, from its own thread.
#include <atomic>
#include <cstdint>
#include <thread>

#include "skyview/core/error.h"

namespace skyview {

// Thrown where a run's progress was cancelled (a Python progress callback said stop).
class Cancelled : public Error {
 public:
  Cancelled() : Error("cancelled") {}
};

class ProgressCounter {
 public:
  void set_total(std::uint64_t total) { total_.store(total == 0 ? 1 : total); }
  void advance(std::uint64_t n = 1) { done_.fetch_add(n, std::memory_order_relaxed); }
  double fraction() const;

  // Asks the run to stop. The loops check at the start of each unit of work (a direction, a row,
  // a block of rows), where nothing is half done and no other worker waits on it, and throw
  // Cancelled; oneTBB then skips the units not started and rethrows in the caller.
  void cancel() { cancelled_.store(true, std::memory_order_relaxed); }
  bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }
  void stop_if_cancelled() const {
    if (cancelled()) throw Cancelled();
  }

 private:
  std::atomic<std::uint64_t> done_{0};
  std::atomic<std::uint64_t> total_{1};
  std::atomic<bool> cancelled_{false};
};

// Prints progress of `counter` to stderr while alive; silent when `quiet`.
class ProgressReporter {
 public:
  ProgressReporter(const ProgressCounter& counter, bool quiet);
  ~ProgressReporter();  // prints the final "100 - done."
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

 private:
  void print_up_to(double fraction);
  const ProgressCounter& counter_;
  bool quiet_;
  int printed_ = -1;  // last tick printed, in units of 2.5 %
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace skyview
