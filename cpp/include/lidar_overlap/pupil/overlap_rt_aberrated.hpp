// Ray-tracing overlap of a receiver with wavefront aberrations (paper Section 3, step 5, and Appendix B with
// "the number of rays representing each emitter increased"): each scatterer sends a fan of rays through the
// pupil (rings equally spaced in area, equally spaced angles); a ray leaves the lens with the paraxial slope of
// B15-B17 plus the wavefront slope grad W, so it lands on the detector plane at
//   u = a (1 + d/z - d/f) - P d/z + d grad_a W(a; P/z),
// and counts if it lands on the detector, misses the obstruction and is within the fibre's NA. Along each ring
// the detector edge is located between rays by linear interpolation of the margin, so the fan converges as
// (1/rays)^2 rather than 1/rays. Seidel terms follow each scatterer's field angle P/z; Zernike terms are the
// same for all. The beam integral is adaptive (as overlap_rt), radial when the scene and the aberrations are
// rotationally symmetric.
// When the rays' displacements are the same for every scatterer (Zernike terms and W040 only, no NA cone,
// obstruction absent or in the aperture plane), G is instead one smooth integral over the pupil of the share of
// the Gaussian beam image that each ray's displacement leaves on the detector: no ray fan, no beam integral
// (src/pupil/aberrated_pupil_integral.hpp).
#pragma once

#include <cstddef>
#include <vector>

#include "lidar_overlap/pupil/aberrations.hpp"
#include "lidar_overlap/core/system.hpp"

namespace lidar_overlap {

// Rays one range's ray-fan integrals may trace (field-dependent terms, NA, obstruction in front): a few seconds.
inline constexpr double kMaxFanRays = 3e8;

struct RtAberratedOptions {
  std::size_t rings = 48;       // rays per scatterer: rings equally spaced in rho^2 ...
  std::size_t ring_rays = 128;  // ... times rays per ring
  double tolerance = 1e-4;      // absolute, on G, for the beam integral
  std::size_t directions =
      64;           // cap on the directions of the beam integral (from 8, doubled until it
                    // converges) when the scene is not rotationally symmetric
  int threads = 0;  // OpenMP threads across ranges; 0: all cores, per call. Callers that run
                    // calls from several threads pass 1 (or their share): core/limits.hpp
  std::size_t max_segments =
      4000;  // per adaptive integral, as overlap_rt; reaching it clears `converged`
};

struct RtAberratedOverlap {
  std::vector<double> overlap;  // G(z)
  std::vector<double>
      error_estimate;  // of the beam integral (the ray fan's own error is ~(1/rays)^2)
  std::vector<bool> converged;
  bool rotationally_symmetric = false;  // one radial integral per range
  bool pupil_form = false;              // computed as one pupil integral per range (see below)
};

// Throws std::invalid_argument for an invalid system, aberration set, range or option, naming it.
RtAberratedOverlap overlap_rt_aberrated(const LidarSystem& system, const Aberrations& aberrations,
                                        const std::vector<double>& ranges,
                                        const RtAberratedOptions& options = {});

// One scatterer costs one fan, not a beam integral of them: 96 x 256 rays buy ~10x its accuracy (docs/aberrations.md).
inline RtAberratedOptions point_coupling_options() {
  RtAberratedOptions o;
  o.rings = 96;
  o.ring_rays = 256;
  return o;
}

// Coupling of one point scatterer at (position, z): the fraction of its rays into the full aperture that count.
double emitter_coupling_rt_aberrated(const LidarSystem& system, const Aberrations& aberrations,
                                     double z, Vec2 position,
                                     const RtAberratedOptions& options = point_coupling_options());

}  // namespace lidar_overlap
