#include "lidar_overlap/core/cancel.hpp"

#include <utility>

#include "core/parallel.hpp"

namespace lidar_overlap {
namespace {
thread_local CancelScope* tl_scope = nullptr;  // the innermost scope of this thread
}  // namespace

CancelScope::CancelScope(std::function<bool()> should_stop, std::chrono::milliseconds interval)
    : should_stop_(std::move(should_stop)),
      interval_(interval),
      next_(std::chrono::steady_clock::now()),
      outer_(tl_scope) {
  tl_scope = this;
}

CancelScope::~CancelScope() { tl_scope = outer_; }

bool CancelScope::poll() {
  if (stopped_ || !should_stop_) return stopped_;
  const auto now = std::chrono::steady_clock::now();
  if (now < next_) return false;
  next_ = now + interval_;
  stopped_ = should_stop_();
  return stopped_;
}

namespace detail {

std::atomic<bool>*& current_stop_flag() {
  thread_local std::atomic<bool>* flag = nullptr;
  return flag;
}

void cancellation_point() {
  std::atomic<bool>* const flag = current_stop_flag();
  if (flag && flag->load(std::memory_order_relaxed)) throw Cancelled();
  // An exception of should_stop propagates as it is: the enclosing parallel_for records it first and only
  // then raises the stop flag, so that no sibling's Cancelled can take its place.
  if (tl_scope && tl_scope->poll()) throw Cancelled();
}

}  // namespace detail
}  // namespace lidar_overlap
