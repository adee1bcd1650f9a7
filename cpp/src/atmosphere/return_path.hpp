// The return path of the turbulent FO overlap (paper Section 3, step 4, through the atmosphere of step 2), by
// reciprocity: the power a point scatterer at x sends onto the detector equals the irradiance at x of the
// detector's light sent out backwards through lens, aperture and the same phase screens. The detector is
// incoherent (a field stop or fibre core many diffraction spots wide), so that light is a partially coherent
// field: here M random-phase realisations. Each is the detector disc (8 samples per radius) with an independent
// uniform random phase per sample, transformed onto the pupil by a direct (matrix) Fourier sum (the lens maps
// detector points to plane waves, the defocus adds the curvature that focuses them at the conjugate range), cut
// by the aperture and the obstruction, then carried to the sky on the beam's grids through the beam's screens.
// The mean of |V_m|^2 over the M fields is the receiver's sensitivity, unbiased for every M; its speckle
// (contrast 1 per field, correlated over lambda z / D) averages over the beam: relative noise ~ 1 / sqrt(M x
// speckles under the beam) per draw, an independent noise that the standard error over realisations already
// contains; each draw states its own (the fields' spread over sqrt(M): independent given the atmosphere).
//
// Normalisation (G's, docs/turbulence.md): a sample of unit amplitude stands for a delta-correlated detector
// field, so the pupil field's mean irradiance is A_det / (lambda d)^2 and, in vacuum, its irradiance at range
// z inside the field of view's footprint is A_ap / (lambda z)^2: S = |V|^2 (lambda z)^2 / A_ap is 1 where every
// ray of a scatterer reaches the detector. The obstruction is applied in the aperture plane (it sits
// obstruction_distance in front of it: its shadow on a scatterer's pupil moves by x z_obs / z, negligible at
// the ranges a turbulent path reaches).
#pragma once

#include <cstdint>
#include <vector>

#include "lidar_overlap/core/system.hpp"
#include "lidar_overlap/fourier/field.hpp"

namespace lidar_overlap::detail {

class ReturnPath {
 public:
  // The pupil plane's grid: n x n samples of `spacing` (m) centred on the beam's axis at range 0.
  ReturnPath(const LidarSystem& system, std::size_t n, double spacing, std::size_t fields);

  // Random-phase field `m` of realisation `k` in the stream `seed` on the pupil grid (beam coordinates; a
  // tilted beam's grid drifts with it, so the field carries the opposite tilt).
  Field pupil_field(std::uint64_t seed, std::size_t k, std::size_t m) const;

  // Radius (m) of the receiver's light at range z about the receiver's axis, geometric: the aperture's
  // image of the detector (defocus included).
  double footprint(double z) const;
  // Largest angle (rad) of the receiver's light: the field of view plus the convergence to the conjugate range.
  double max_angle() const;

  std::size_t fields() const { return fields_; }
  double aperture_area() const { return area_; }

 private:
  static constexpr int kSamples = 8;  // detector samples per radius
  const LidarSystem& system_;
  std::size_t n_, fields_;
  double spacing_, lambda_, d_, area_, step_ = 0.0;
  std::vector<Vec2> detector_;           // m, samples on the detector plane inside its disc
  std::vector<double> detector_weight_;  // sqrt(area share) of each sample's cell inside the disc
  std::vector<Complex> kernel_x_, kernel_y_;  // [detector column or row][pupil index]
};

}  // namespace lidar_overlap::detail
