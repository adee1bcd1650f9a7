// One entry of the ray-tracing overlap (G of one system at one range), shared by overlap_rt, its batch
// form and alignment_map so that all of them give the same bits. Internal header, not installed.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "geometry/receiver_coupling.hpp"
#include "lidar_overlap/geometry/overlap_rt.hpp"

namespace lidar_overlap::detail {

struct RtEntry {
  double value = 0.0, error = 0.0;
  std::size_t evaluations = 0;
  bool converged = true;
  void add(const RtEntry& o) {
    value += o.value;
    error += o.error;
    evaluations += o.evaluations;
    converged = converged && o.converged;
  }
};

// Checks the options every RT entry point shares (tolerance, max_segments); throws std::invalid_argument.
void check_rt_options(const RtOptions& options);

// G of `system` at the receiver's range. Does not throw for a valid system, range and options.
RtEntry overlap_rt_entry(const LidarSystem& system, const Receiver& receiver, const RtOptions& options);

// Entries as an RtOverlap (axisymmetric left false), each checked like a single call: finite, in [0, 1] up
// to max(tolerance, its own error) (checks::overlap_values, naming `method` and ranges[i]).
RtOverlap collect_rt_entries(const std::vector<RtEntry>& entries, const std::vector<double>& ranges,
                             double tolerance, const std::string& method);

}  // namespace lidar_overlap::detail
