// The range loop shared by the RT entry points over one system (full aperture, masked): the entry checks,
// the receivers built before the parallel region (nothing throws inside it), one beam integral per range in
// parallel, and the result's assembly and value checks. Internal header, not installed.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "lidar_overlap/geometry/overlap_rt.hpp"
#include "geometry/beam_integral.hpp"
#include "geometry/receiver_coupling.hpp"

namespace lidar_overlap::detail {

// `at(receiver)` at every range; `name` is the engine's name in value errors. `at` must not throw.
RtOverlap rt_over_ranges(const LidarSystem& system, const std::vector<double>& ranges, const RtOptions& options,
                         const std::function<beam_integral::RangeResult(const Receiver&)>& at,
                         const std::string& name);

}  // namespace lidar_overlap::detail
