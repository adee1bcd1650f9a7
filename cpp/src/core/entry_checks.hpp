// The checks every overlap entry point makes on its ranges and its `threads` option before it computes.
// Internal header, not installed.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "lidar_overlap/core/system.hpp"

namespace lidar_overlap::detail {

// "ranges[i]": how errors name the i-th range of a call.
std::string range_name(std::size_t i);

// Checks `threads` (thread_count, core/parallel.hpp) and then every range (LidarSystem::validate_range, each
// named ranges[i]); returns the OpenMP team size for the call.
int checked_threads_and_ranges(const LidarSystem& system, const std::vector<double>& ranges,
                               int threads);

// The same for a batch where ranges[i] belongs to systems[i] (sizes checked by the caller); each system is
// validated first, its errors prefixed with "systems[i]: ".
int checked_threads_and_ranges(const std::vector<LidarSystem>& systems,
                               const std::vector<double>& ranges, int threads);

}  // namespace lidar_overlap::detail
