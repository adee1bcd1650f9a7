// One entry of the ray-tracing overlap (G of one system at one range), shared by overlap_rt, its batch
// form, alignment_map and the masked overlap so that all of them give the same bits. Internal header, not
// installed.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "geometry/beam_integral.hpp"
#include "geometry/receiver_coupling.hpp"
#include "lidar_overlap/geometry/overlap_rt.hpp"

namespace lidar_overlap::detail {

// One beam integral's value, error bound, evaluations and convergence.
using RtEntry = beam_integral::RangeResult;

// Checks the options every RT entry point shares (tolerance, max_segments); throws std::invalid_argument.
void check_rt_options(const RtOptions& options);

// G of `system` at the receiver's range. Does not throw for a valid system, range and options.
RtEntry overlap_rt_entry(const LidarSystem& system, const Receiver& receiver, const RtOptions& options);

// Entries as an RtOverlap (axisymmetric left false), each checked like a single call: finite, in [0, 1] up
// to max(tolerance, its own error) (checks::overlap_values, naming `method` and ranges[i]).
RtOverlap collect_rt_entries(const std::vector<RtEntry>& entries, const std::vector<double>& ranges,
                             double tolerance, const std::string& method);

// The range loop of the RT entry points over one system (full aperture, masked): the entry checks, the
// receivers built before the parallel region (nothing throws inside it), `at(receiver)` at every range in
// parallel, and the result's assembly and value checks; `name` is the engine's name in value errors.
RtOverlap rt_over_ranges(const LidarSystem& system, const std::vector<double>& ranges, const RtOptions& options,
                         const std::function<RtEntry(const Receiver&)>& at, const std::string& name);

}  // namespace lidar_overlap::detail
