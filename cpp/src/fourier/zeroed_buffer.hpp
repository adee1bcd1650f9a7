// A zero-filled ComplexBuffer whose filling can be cancelled: a grid of 8192^2 or more takes seconds of a
// busy core to zero, longer than a Ctrl-C may wait. Internal header, not installed.
#pragma once

#include <algorithm>
#include <cstddef>

#include "core/cancel_every.hpp"
#include "lidar_overlap/fourier/complex_buffer.hpp"

namespace lidar_overlap::detail {

// count zeros, filled 2^20 samples (16 MB) at a time with a cancellation point before each: the same buffer
// as ComplexBuffer(count, Complex{}), allocated once.
inline ComplexBuffer zeroed_buffer(std::size_t count) {
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  ComplexBuffer b;
  b.reserve(count);
  while (b.size() < count) {
    cancellation_point();
    b.resize(std::min(count, b.size() + kChunk));
  }
  return b;
}

}  // namespace lidar_overlap::detail
