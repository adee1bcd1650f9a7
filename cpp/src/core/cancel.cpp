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
  if (!tl_scope) return;
  bool stop = false;
  try {
    stop = tl_scope->poll();
  } catch (...) {
    if (flag) flag->store(true);
    throw;
  }
  if (stop) {
    if (flag) flag->store(true);
    throw Cancelled();
  }
}

}  // namespace detail
}  // namespace lidar_overlap
