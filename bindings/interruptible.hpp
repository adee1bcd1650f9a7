// Long core calls from Python: the GIL released around the compute, and Ctrl-C honoured within ~0.1 s.
#pragma once

#include <pybind11/pybind11.h>

#include <atomic>

#include "lidar_overlap/core/cancel.hpp"

// For its lifetime: the GIL is released, and the core asks Python for pending signals between ranges,
// realisations and iterations. On Ctrl-C the call stops with lidar_overlap::Cancelled, which the module
// turns into the pending KeyboardInterrupt.
// interrupt_requested(): set by the package's SIGINT handler while a long Python-level call runs
// (lidar_overlap._interrupts). Python runs signal handlers in the main thread only, so a call made in a
// worker thread (a Dask task) would never see Ctrl-C through PyErr_CheckSignals; the flag reaches it.
inline std::atomic<bool>& interrupt_requested() {
  static std::atomic<bool> flag{false};
  return flag;
}

class Interruptible {
 public:
  Interruptible()
      : scope_([] {
          if (interrupt_requested().load(std::memory_order_relaxed)) return true;
          pybind11::gil_scoped_acquire gil;
          return PyErr_CheckSignals() != 0;  // leaves KeyboardInterrupt set for the caller
        }) {}

 private:
  lidar_overlap::CancelScope scope_;  // made while the GIL is held, ended after it is back
  pybind11::gil_scoped_release release_;
};
