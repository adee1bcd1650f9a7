// Alignment maps: the ray-tracing overlap G over a grid of misalignments (one or two axes) at chosen
// ranges, every grid point's system built and integrated inside one parallel call.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "lidar_overlap/core/system.hpp"
#include "lidar_overlap/geometry/overlap_rt.hpp"

namespace lidar_overlap {

// A scalar of the system a map varies; its name is the one errors use and Python's keyword.
enum class AlignmentParameter {
  tilt_x,             // beam.tilt.x, rad
  tilt_y,             // beam.tilt.y, rad
  beam_offset_x,      // beam.offset.x, m
  beam_offset_y,      // beam.offset.y, m
  detector_offset_x,  // detector.offset.x, m
  detector_offset_y,  // detector.offset.y, m
  defocus,            // detector.defocus, m
};

// "tilt_x", "beam_offset_y", ...; and back (throws std::invalid_argument naming `parameter` for a name
// that is none of them).
const char* alignment_parameter_name(AlignmentParameter p);
AlignmentParameter alignment_parameter_from_name(const std::string& name,
                                                 const std::string& parameter = "axes");

// One axis of a map: values (rad or m, finite, strictly increasing) added to the system's own value.
struct AlignmentAxis {
  AlignmentParameter parameter = AlignmentParameter::tilt_x;
  std::vector<double> values;
};

// `system` with `delta` added to its scalar `p` (not validated).
LidarSystem misaligned(const LidarSystem& system, AlignmentParameter p, double delta);

// Most grid points one map takes, and most (grid point, range) entries (each an adaptive integral,
// ~0.1-10 ms); the memory budget (max_memory) bounds the arrays too.
inline constexpr std::size_t kMaxAlignmentPoints = 1000000;
inline constexpr std::size_t kMaxAlignmentEntries = kMaxBatchEntries;

struct AlignmentMap {
  std::vector<std::size_t> shape;  // the axes' sizes, then the number of ranges
  RtOverlap values;                // entry ((i0 * n1 + i1) * n_ranges + k): row-major over `shape`
};

// G at every grid point of `axes` (1 or 2 axes, distinct parameters) and range (m), each entry bit for bit
// overlap_rt(misaligned system, {range}, options), in parallel over all entries; entries that are the same
// computation (axes that only move the beam, its centre at the same distance from the receiver's centre of
// symmetry: the mirror images of a symmetric grid) are made once and copied, and `values.evaluations` counts
// each entry as made alone. `values.axisymmetric` is
// true when every grid point's system is. Throws std::invalid_argument naming the axis (e.g.
// "tilt_x[3]") for a non-finite or unsorted value or one that makes an invalid system, "axes" for their
// count or a repeated parameter, and the size for grids beyond the caps or the memory budget.
AlignmentMap alignment_map(const LidarSystem& system, const std::vector<AlignmentAxis>& axes,
                           const std::vector<double>& ranges, const RtOptions& options = {});

}  // namespace lidar_overlap
