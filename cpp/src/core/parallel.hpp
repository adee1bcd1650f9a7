// Loops over ranges (or realisations) on OpenMP threads, safely: an exception thrown by one iteration
// stops the others at their next cancellation point and is rethrown on the calling thread once the
// region has ended (an exception escaping an OpenMP region would terminate the process), and the
// caller's CancelScope is asked between iterations (and, once the calling thread has none left, while the
// other threads finish theirs). Internal header, not installed.
#pragma once

#include <omp.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
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

// The OpenMP team size for the user's `threads` option: 0 means all cores (all_cores()); a negative count
// or one above max_threads() throws std::invalid_argument naming the option.
int thread_count(int requested);

// Thread policy for `threads = 0` on a busy machine. A team cannot end before its last thread has started,
// and on a loaded machine a thread may wait several scheduler time slices to start: a call of a few
// milliseconds then takes many times its one-thread time. Every team reports when its last thread started;
// one that started late (> 1 ms and > 1/4 of the region) makes all_cores() answer 1 for the next second,
// after which a full team is tried again. Explicit counts are always honoured. Results do not depend on it.
int all_cores();
void note_team_start(int threads, long long latest_start_ns, long long region_ns);

// Measures when the threads of one team start (TeamClock clock; in the region: clock.started(); after
// it: clock.report(threads)).
class TeamClock {
 public:
  TeamClock() : start_(now_ns()) {}
  void started() {
    const long long late = now_ns() - start_;
    long long seen = latest_.load(std::memory_order_relaxed);
    while (late > seen && !latest_.compare_exchange_weak(seen, late, std::memory_order_relaxed)) {
    }
  }
  void report(int threads) const { note_team_start(threads, latest_.load(), now_ns() - start_); }

 private:
  static long long now_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
  }
  long long start_;
  std::atomic<long long> latest_{0};
};

// How often the calling thread asks its CancelScope while other threads finish the last iterations of a
// parallel_for (the scope itself asks Python at most every 0.1 s).
inline constexpr std::chrono::milliseconds kFinishPoll{20};

// body(i) for i in [0, count) on `threads` threads (from thread_count), dynamic schedule.
template <class Body>
void parallel_for(std::size_t count, int threads, Body&& body) {
  // The calling thread's scope is asked once before the region: with a dynamic schedule the other threads
  // may take every iteration of a short loop before the calling thread reaches it.
  cancellation_point();
  std::atomic<bool> stop{false};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto fail = [&] {
    std::lock_guard<std::mutex> lock(failure_mutex);
    if (!failure) failure = std::current_exception();
    stop.store(true);
  };
  // Iterations ended (run, skipped or failed), and the calling thread's wait for the last of them.
  std::atomic<std::size_t> ended{0};
  std::mutex ended_mutex;
  std::condition_variable all_ended;
  TeamClock clock;
#pragma omp parallel num_threads(threads)
  {
    clock.started();
    std::atomic<bool>*& flag = current_stop_flag();
    std::atomic<bool>* const enclosing = flag;
    flag = &stop;
#pragma omp for schedule(dynamic, 1) nowait
    for (long i = 0; i < static_cast<long>(count); ++i) {
      if (!stop.load(std::memory_order_relaxed)) {
        try {
          cancellation_point();
          body(static_cast<std::size_t>(i));
        } catch (...) {
          fail();
        }
      }
      if (ended.fetch_add(1) + 1 == count) {
        std::lock_guard<std::mutex> lock(ended_mutex);
        all_ended.notify_all();
      }
    }
    // Only the calling thread (thread 0) has a CancelScope. Once it has no iteration left it keeps asking
    // it while the others finish theirs, so that Ctrl-C also stops a long last iteration (or the only one)
    // that another thread runs; the request reaches that iteration through the stop flag.
    if (omp_get_thread_num() == 0 && omp_get_num_threads() > 1) {
      std::unique_lock<std::mutex> lock(ended_mutex);
      while (!all_ended.wait_for(lock, kFinishPoll, [&] { return ended.load() == count; })) {
        if (stop.load(std::memory_order_relaxed)) continue;
        lock.unlock();
        try {
          cancellation_point();
        } catch (...) {
          fail();
        }
        lock.lock();
      }
    }
    flag = enclosing;
  }
  clock.report(threads);
  if (failure) std::rethrow_exception(failure);
}

}  // namespace lidar_overlap::detail
