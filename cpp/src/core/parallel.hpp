// Loops over ranges (or realisations) on OpenMP threads, safely: an exception thrown by one
// iteration stops the others at their next cancellation point and is rethrown on the calling thread
// once the region has ended (an exception escaping an OpenMP region would terminate the process),
// and the caller's CancelScope is asked between iterations (and, once the calling thread has none
// left, while the other threads finish theirs). Internal header, not installed.
#pragma once

#include <omp.h>
#include <time.h>

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

// The OpenMP team size for the user's `threads` option: 0 means all cores (all_cores()); a negative
// count or one above max_threads() throws std::invalid_argument naming the option.
int thread_count(int requested);

// Thread policy for `threads = 0` on a busy machine. An OpenMP team cannot end before its last
// thread has started and finished, and on a loaded machine a thread may wait several scheduler time
// slices to start, or be descheduled in the middle of its work: a call of a few milliseconds then
// takes many times its one-thread time. Every team reports how long it waited for a core (a
// thread's late start, also where the passes' team did not wait for it; the passes' caller's wait
// for a member descheduled in its work; wall time in the region beyond a thread's CPU time); a team
// that waited long (> 1 ms and > 1/4 of the region) makes all_cores() answer 1 for the next 0.1 s
// (doubled by each further late team within twice the last hold, up to 1 s), after which a full
// team is tried again. Explicit counts are always honoured. Results do not depend on it.
int all_cores();
// True while a late team holds all_cores() to one thread: the machine is busy.
bool machine_busy();
// All cores whether or not a late team holds all_cores() to one thread: for the transforms' passes,
// whose team (core/team.hpp) never waits for a thread that starts late, while one thread on a busy
// machine gets one share of the cores against every other process's full team (the scheduler shares
// per thread).
int all_cores_even_if_busy();
void note_team_wait(int threads, long long waited_ns, long long region_ns);

// The steady clock in nanoseconds: the times of the thread policy below.
inline long long steady_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

// Measures how long the threads of one team waited for a core (TeamClock clock; in the region:
// `const auto mark = clock.started();` first and `clock.finished(mark);` once the thread's share of
// the work is done, before any wait for the others; after the region: clock.report(threads)). A
// team that does not wait for a thread that starts late (core/team.hpp) also notes the caller's
// wait for those still in their work with waited().
class TeamClock {
 public:
  struct Mark {
    long long wall_ns, cpu_ns;
  };
  TeamClock() : start_(steady_ns()) {}
  Mark started() {
    const Mark mark{steady_ns(), cpu_ns()};
    note(mark.wall_ns - start_);
    return mark;
  }
  void waited(long long ns) { note(ns); }
  // Wall time the thread spent in its work beyond its CPU time: time descheduled (page faults and
  // system calls count as CPU time; the work blocks on nothing else).
  void finished(const Mark& mark) { note((steady_ns() - mark.wall_ns) - (cpu_ns() - mark.cpu_ns)); }
  void report(int threads) const { note_team_wait(threads, waited_.load(), steady_ns() - start_); }

 private:
  static long long cpu_ns() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<long long>(t.tv_sec) * 1'000'000'000LL + t.tv_nsec;
  }
  void note(long long waited) {
    long long seen = waited_.load(std::memory_order_relaxed);
    while (waited > seen &&
           !waited_.compare_exchange_weak(seen, waited, std::memory_order_relaxed)) {}
  }
  long long start_;
  std::atomic<long long> waited_{0};
};

// How often the calling thread asks its CancelScope while other threads finish the last iterations
// of a parallel_for (the scope itself asks Python at most every 0.1 s).
inline constexpr std::chrono::milliseconds kFinishPoll{20};

// body(i) for i in [0, count) on `threads` threads (from thread_count), dynamic schedule.
template <class Body>
void parallel_for(std::size_t count, int threads, Body&& body) {
  // The calling thread's scope is asked once before the region: with a dynamic schedule the other
  // threads may take every iteration of a short loop before the calling thread reaches it.
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
    const TeamClock::Mark mark = clock.started();
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
    clock.finished(mark);
    // Only the calling thread (thread 0) has a CancelScope. Once it has no iteration left it keeps
    // asking it while the others finish theirs, so that Ctrl-C also stops a long last iteration (or
    // the only one) that another thread runs; the request reaches that iteration through the stop
    // flag.
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
