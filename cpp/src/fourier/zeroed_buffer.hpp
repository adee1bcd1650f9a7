// Zero-filled buffers whose filling can be cancelled: a grid of 8192^2 or more takes seconds of a busy core
// to zero, longer than a Ctrl-C may wait. Internal header, not installed.
#pragma once

#include <algorithm>
#include <cstddef>

#include "core/cancel_every.hpp"
#include "lidar_overlap/fourier/complex_buffer.hpp"

namespace lidar_overlap::detail {

// count zero values, filled 2^20 at a time (16 MB of Complex) with a cancellation point before each: the same
// buffer as Buffer(count), allocated once.
template <class Buffer = ComplexBuffer>
Buffer zeroed_buffer(std::size_t count) {
  constexpr std::size_t kChunk = std::size_t{1} << 20;
  Buffer b;
  b.reserve(count);
  while (b.size() < count) {
    cancellation_point();
    b.resize(std::min(count, b.size() + kChunk));
  }
  return b;
}

}  // namespace lidar_overlap::detail
