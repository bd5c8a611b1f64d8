// Long work that Ctrl-C can stop, as Python users expect of a call that takes seconds.
#pragma once

#include <atomic>
#include <chrono>
#include <future>
#include <utility>

#include <pybind11/pybind11.h>

#include "pss/core/cancel.hpp"

namespace pss::python {

namespace py = pybind11;

// Runs `work` on a worker thread without the GIL while this thread waits, answering signals
// (Python's handlers run on the main thread only): on KeyboardInterrupt it sets the work's
// cancel flag, so that the CPU backend skips the chunks not yet begun (core/cancel.hpp),
// waits for the worker to finish early, drops its result and raises. Errors of the work are
// rethrown here.
template <class Work>
auto run_interruptibly(Work&& work) -> decltype(work()) {
  std::atomic<bool> cancel{false};
  auto result = std::async(std::launch::async, [&] {
    const CancelScope scope(&cancel);
    return work();
  });
  for (;;) {
    {
      const py::gil_scoped_release release;  // Python's other threads run while the work does
      if (result.wait_for(std::chrono::milliseconds(50)) == std::future_status::ready) break;
    }
    if (PyErr_CheckSignals() != 0) {
      cancel = true;
      {
        const py::gil_scoped_release release;
        result.wait();
      }
      throw py::error_already_set();
    }
  }
  return result.get();
}

}  // namespace pss::python
