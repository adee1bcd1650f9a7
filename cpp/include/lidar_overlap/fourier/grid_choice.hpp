// The grid a propagation needs (paper Appendix A's sampling conditions made automatic): how far to
// zero-pad a field so that the propagated field neither wraps around nor is clipped, the angular
// spectrum's band limit keeps its power, and a Fresnel output samples the irradiance at Nyquist.
#pragma once

#include <cstddef>

#include "lidar_overlap/fourier/field.hpp"
#include "lidar_overlap/fourier/propagate.hpp"

namespace lidar_overlap {

struct GridChoice {
  std::size_t n;             // grid size to zero-pad to (>= the input's)
  PropagationMethod method;  // the method for that grid (the one asked for, or auto's choice)
  double input_radius;       // m, radius about the axis holding all but 1e-7 of the input power
  double angular_radius;  // rad, the same for the plane-wave spectrum (lambda x spatial frequency)
  double
      output_radius;  // m, bound on the radius at the distance: input_radius + |z| angular_radius
};

// Smallest power-of-two grid (>= in.n) for propagating `in` over `distance` (m) with `method`. Throws
// std::invalid_argument naming "grid_size" if it exceeds max_n.
GridChoice choose_grid(const Field& in, double distance, PropagationMethod method,
                       std::size_t max_n = 8192);

// `in` centred in an n x n grid of zeros (n >= in.n, n even): same spacing, same coordinates.
Field zero_pad(const Field& in, std::size_t n);

}  // namespace lidar_overlap
