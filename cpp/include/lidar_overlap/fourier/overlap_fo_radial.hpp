// Fourier-optics overlap of a Gaussian beam in one dimension. When the beam is a Gaussian (TEM00, or M^2 > 1
// as a Gaussian Schell-model beam), the irradiance at every range is the Gaussian of radius w(z), whose
// transform is exp(-pi^2 w^2 f^2 / 2), and the receiver's OTF depends on |q| only. Its image on the detector
// plane (radius w_i = w(z) d / z) is centred s away from the detector centre (s = 0 for an axisymmetric
// lidar; beam offset, tilt and detector offset move it), and the Parseval sum of overlap_fo becomes one
// Hankel-type integral:
//   G(z) = (2 pi / pi R^2) int_0^qc OTF(q) disc^(q) exp(-pi^2 w_i^2 q^2 / 2) J0(2 pi q s) q dq,
// with no grids, no padding and no aliasing: composite Gauss-Legendre over panels of a few periods of
// the integrand's fastest oscillation (detector disc, point-image blur or image offset).
#pragma once

#include <cstddef>
#include <vector>

#include "lidar_overlap/core/system.hpp"

namespace lidar_overlap {

struct RadialFoOptions {
  double periods_per_panel =
      8.0;          // panel length in periods of the fastest oscillation (24 nodes each)
  int threads = 0;  // OpenMP threads across ranges; 0: all cores, per call. Callers that run
                    // calls from several threads pass 1 (or their share): core/limits.hpp
};

struct RadialFoOverlap {
  std::vector<double> overlap;           // G(z)
  std::vector<std::size_t> evaluations;  // OTF evaluations per range
};

// Throws std::invalid_argument unless the beam follows the Gaussian width law with a divergence at or above
// lambda / (pi w0).
RadialFoOverlap overlap_fo_radial(const LidarSystem& system, const std::vector<double>& ranges,
                                  const RadialFoOptions& options = {});

}  // namespace lidar_overlap
