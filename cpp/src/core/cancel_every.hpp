// Cancellation inside long loops that are not parallel_for iterations of their own. Internal header,
// not installed.
#pragma once

#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>

#include "core/parallel.hpp"

namespace lidar_overlap::detail {

// cancellation_point() on every 1024th pass of a long loop (i = the pass): serial set-up loops over
// millions of ranges or grid points, and the inner loops of a long iteration, then stop within a few
// milliseconds of the request, at the cost of one clock read per 1024 passes.
inline void cancellation_point_every(std::size_t i) {
  if ((i & 1023u) == 0) cancellation_point();
}

// Cancellation inside a plain OpenMP region (a pass over the rows or blocks of one large grid), where no
// exception may cross the region's boundary: every thread asks stopped() before each row or block and
// skips it once it answers true; after the region, rethrow() raises what stopped it (Cancelled, or the
// exception of the caller's should_stop). Only the calling thread's scope is asked (the team's other
// threads see the stop flag of an enclosing parallel_for, or nothing), and rows are skipped only once
// the call is lost anyway, so results are the same bits whenever it is not cancelled.
class RegionStop {
 public:
  bool stopped() {
    if (stop_.load(std::memory_order_relaxed)) return true;
    try {
      cancellation_point();
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!failure_) failure_ = std::current_exception();
      stop_.store(true);
    }
    return stop_.load(std::memory_order_relaxed);
  }
  void rethrow() const {
    if (failure_) std::rethrow_exception(failure_);
  }

 private:
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::exception_ptr failure_;
};

}  // namespace lidar_overlap::detail
