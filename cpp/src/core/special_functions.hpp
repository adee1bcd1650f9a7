// Special functions the overlap integrals share.
#pragma once

#include <cmath>

#include "core/constants.hpp"

namespace lidar_overlap {

// exp(-x) I0(x) for x >= 0, without overflow.
inline double scaled_bessel_i0(double x) {
  if (x < 500.0) return std::cyl_bessel_i(0.0, x) * std::exp(-x);
  // Hankel's asymptotic series; at x >= 500 four terms are exact to double precision.
  const double t = 1.0 / (8.0 * x);
  return (1.0 + t * (1.0 + t * (9.0 / 2.0 + t * (225.0 / 6.0)))) / std::sqrt(2.0 * kPi * x);
}

}  // namespace lidar_overlap
