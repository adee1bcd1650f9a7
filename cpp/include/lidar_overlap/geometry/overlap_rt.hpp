// Ray-tracing overlap function G(z) (paper Appendix B, Sections 4A-4B): the beam irradiance at each
// range, weighted by the exact paraxial coupling of every scatterer (src/geometry/receiver_coupling.hpp),
// integrated by adaptive quadrature to an absolute tolerance on G instead of a fixed emitter grid.
#pragma once

#include <cstddef>
#include <vector>

#include "lidar_overlap/core/system.hpp"

namespace lidar_overlap {

struct RtOptions {
  double tolerance = 1e-4;  // absolute error allowed on G at each range, in (0, 1)
  int threads = 0;  // OpenMP threads across ranges; 0: all cores, per call. Callers that run
                    // calls from several threads pass 1 (or their share): core/limits.hpp
  std::size_t max_segments = 4000;  // per adaptive integral; reaching it clears `converged`
};

struct RtOverlap {
  std::vector<double> overlap;         // G(z), dimensionless, one per range
  std::vector<double> error_estimate;  // estimated absolute error of each G(z)
  std::vector<bool> converged;         // false where the tolerance was not reached
  std::size_t evaluations = 0;         // scatterer couplings computed, all ranges
  bool axisymmetric = false;           // beam and receiver share the telescope axis
};

// G at every range (m, each > 0 and beyond the obstruction). Thread-safe; results do not depend on
// the thread count. Throws std::invalid_argument for an invalid system, range or option.
RtOverlap overlap_rt(const LidarSystem& system, const std::vector<double>& ranges,
                     const RtOptions& options = {});

// Most entries one overlap_rt_batch call takes (each costs an adaptive integral, ~0.1-10 ms).
inline constexpr std::size_t kMaxBatchEntries = 10000000;

// Entry i is G of systems[i] at ranges[i] (m), bit for bit what overlap_rt(systems[i], {ranges[i]}, options)
// gives, computed in parallel over entries: many systems (e.g. wandering beams) in one call. `axisymmetric`
// is true when every system is. Throws std::invalid_argument for sizes that differ or exceed
// kMaxBatchEntries, and for an invalid system (naming systems[i]), range (ranges[i]) or option.
RtOverlap overlap_rt_batch(const std::vector<LidarSystem>& systems,
                           const std::vector<double>& ranges, const RtOptions& options = {});

// Coupling of one point scatterer at (position, z) (m): power reaching the detector over the power
// it sends into the full, unobstructed aperture.
double emitter_coupling_rt(const LidarSystem& system, double z, Vec2 position);

}  // namespace lidar_overlap
