#include "progress_callback.h"

#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

#include "skyview/core/error.h"

namespace skyview::python {

namespace py = pybind11;

namespace {

constexpr auto kInterval = std::chrono::milliseconds(100);

// Whether the callback lets the run go on; a Python exception stays in `raised`.
bool keep_going(const py::object& callback, double fraction, std::optional<py::error_already_set>& raised) {
  try {
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    const py::object answer = callback(fraction);
    return !(py::isinstance<py::bool_>(answer) && !answer.cast<bool>());
  } catch (py::error_already_set& e) {
    raised.emplace(std::move(e));
    return false;
  }
}

}  // namespace

void run_with_progress(const py::object& callback, const std::function<void(ProgressCounter&)>& work) {
  ProgressCounter progress;
  if (callback.is_none()) {
    py::gil_scoped_release computing;
    work(progress);
    return;
  }
  if (!PyCallable_Check(callback.ptr())) throw UsageError("progress must be a callable taking the fraction done");
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  std::exception_ptr failure;
  std::optional<py::error_already_set> raised;
  bool stopped = !keep_going(callback, 0.0, raised);
  if (stopped) progress.cancel();
  std::thread worker;
  {
    py::gil_scoped_release computing;
    worker = std::thread([&] {
      try {
        work(progress);
      } catch (...) {
        failure = std::current_exception();
      }
      const std::lock_guard<std::mutex> lock(mutex);
      done = true;
      finished.notify_all();
    });
  }
  while (true) {
    {
      py::gil_scoped_release waiting;
      std::unique_lock<std::mutex> lock(mutex);
      if (finished.wait_for(lock, kInterval, [&] { return done; })) break;
    }
    if (!stopped && !keep_going(callback, progress.fraction(), raised)) {
      stopped = true;
      progress.cancel();
    }
  }
  {
    py::gil_scoped_release joining;
    worker.join();
  }
  if (raised) throw std::move(*raised);
  if (stopped) throw Cancelled();
  if (failure) std::rethrow_exception(failure);
  if (!keep_going(callback, 1.0, raised) && raised) throw std::move(*raised);
}

}  // namespace skyview::python
