// Cancelling a long computation. A CancelScope installs, for the calls its thread makes while it lives, a
// question "should this call stop?" that the core asks about ten times a second (from the calling thread
// only, never from OpenMP workers). When it answers true the call stops at its next cancellation point
// (between ranges, realisations, iterations) and throws Cancelled; no partial result is returned.
#pragma once

#include <chrono>
#include <functional>
#include <stdexcept>

namespace lidar_overlap {

struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("the computation was cancelled") {}
};

class CancelScope {
 public:
  // `should_stop` may throw: the call then stops and rethrows that exception instead of Cancelled.
  explicit CancelScope(std::function<bool()> should_stop,
                       std::chrono::milliseconds interval = std::chrono::milliseconds(100));
  ~CancelScope();
  CancelScope(const CancelScope&) = delete;
  CancelScope& operator=(const CancelScope&) = delete;

  // True (and from then on) once should_stop answered true; asks it at most once per interval.
  bool poll();

 private:
  std::function<bool()> should_stop_;
  std::chrono::milliseconds interval_;
  std::chrono::steady_clock::time_point next_;
  bool stopped_ = false;
  CancelScope* outer_;
};

}  // namespace lidar_overlap
