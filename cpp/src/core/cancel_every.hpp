// Cancellation inside long loops that are not parallel_for iterations of their own. Internal header,
// not installed.
#pragma once

#include <cstddef>

#include "core/parallel.hpp"

namespace lidar_overlap::detail {

// cancellation_point() on every 1024th pass of a long loop (i = the pass): serial set-up loops over
// millions of ranges or grid points, and the inner loops of a long iteration, then stop within a few
// milliseconds of the request, at the cost of one clock read per 1024 passes.
inline void cancellation_point_every(std::size_t i) {
  if ((i & 1023u) == 0) cancellation_point();
}

}  // namespace lidar_overlap::detail
