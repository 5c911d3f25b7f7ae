#pragma once
// progress=callable(fraction) of the Python functions: the library's ProgressCounter read from the
// Python thread while the computation runs on another with the GIL released.
#include <pybind11/pybind11.h>

#include <functional>

#include "skyview/core/progress.h"

namespace skyview::python {

// Runs `work` with the GIL released. Without a callback (None) it runs on this thread; with one it
// runs on a thread of its own while this thread calls `callback(fraction)` with the GIL held about
// ten times a second, and once with 1.0 at the end. A callback that returns False, or raises,
// cancels the run (ProgressCounter::cancel): the call then raises the callback's exception, or
// skyview.Error "cancelled". So does Ctrl-C (the interpreter's pending signals are checked too).
void run_with_progress(const pybind11::object& callback, const std::function<void(ProgressCounter&)>& work);

}  // namespace skyview::python
