// Loops over ranges (or realisations) on OpenMP threads, safely: an exception thrown by one iteration
// stops the others at their next cancellation point and is rethrown on the calling thread once the
// region has ended (an exception escaping an OpenMP region would terminate the process), and the
// caller's CancelScope is asked between iterations. Internal header, not installed.
#pragma once

#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>

#include "lidar_overlap/core/cancel.hpp"

namespace lidar_overlap::detail {

// The stop flag of the parallel_for this thread works in (workers included), or null.
std::atomic<bool>*& current_stop_flag();

// Throws Cancelled when the calling thread's CancelScope asks to stop or a sibling iteration of the
// enclosing parallel_for has failed. Cheap enough for every loop that may run for long.
void cancellation_point();

// The OpenMP team size for the user's `threads` option: 0 means all cores; a negative count or one above
// max_threads() throws std::invalid_argument naming the option.
int thread_count(int requested);

// body(i) for i in [0, count) on `threads` threads (from thread_count), dynamic schedule.
template <class Body>
void parallel_for(std::size_t count, int threads, Body&& body) {
  // The calling thread's scope is asked once before the region: with a dynamic schedule the other threads
  // may take every iteration of a short loop before the calling thread reaches it.
  cancellation_point();
  std::atomic<bool> stop{false};
  std::exception_ptr failure;
  std::mutex failure_mutex;
#pragma omp parallel num_threads(threads)
  {
    std::atomic<bool>*& flag = current_stop_flag();
    std::atomic<bool>* const enclosing = flag;
    flag = &stop;
#pragma omp for schedule(dynamic, 1)
    for (long i = 0; i < static_cast<long>(count); ++i) {
      if (stop.load(std::memory_order_relaxed)) continue;
      try {
        cancellation_point();
        body(static_cast<std::size_t>(i));
      } catch (...) {
        std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        stop.store(true);
      }
    }
    flag = enclosing;
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace lidar_overlap::detail
