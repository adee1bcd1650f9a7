// The receiver of the Fourier-optics paths at one range: the pupil seen by a point scatterer (aperture, the
// obstruction's shadow, the NA cone, a second stop, the defocus phase) and the OTF, blur and alias scales derived from it
// (paper Appendix C; fourier/otf.hpp). Shared by the 2-D, radial, aberrated and turbulent FO paths.
// Internal header, not installed.
#pragma once

#include <string>

#include "lidar_overlap/core/system.hpp"
#include "fourier/otf.hpp"

namespace lidar_overlap {

// The receiver of the Fourier-optics path at range z (m).
class FoReceiver {
 public:
  // Throws std::invalid_argument naming `parameter` (the range's name) where the defocus phase across the
  // pupil exceeds kMaxPupilPhase rad: the image is geometric there and its closed-form OTF would cost O(phase).
  FoReceiver(const LidarSystem& system, double z, const std::string& parameter = "z");
  static constexpr double kMaxPupilPhase = 1e7;
  // Work of one OTF evaluation (Bessel terms, ~ the defocus phase across the pupil), and the most work one
  // integral over the OTF may ask for (a few seconds): beyond it the image is geometric and RT is exact.
  double otf_cost() const;
  static constexpr double kMaxOtfWork = 2e9;
  // Coupling (as emitter_coupling_rt) of a point scatterer whose image centre lies `offset` (m) from
  // the detector centre: (2 pi / pi R^2) int OTF disc^ J0(2 pi q offset) q dq.
  double point_coupling(double offset) const;
  // OTF (m^2) at spatial frequency q (1/m) in the detector plane.
  double otf(double q) const { return annular_otf(pupil_, wavelength_ * d_ * q); }
  double detector_distance() const { return d_; }
  double cutoff() const { return 2.0 * pupil_.outer / (wavelength_ * d_); }  // 1/m, OTF = 0 beyond
  // False when no light reaches the detector plane (the obstruction's shadow covers the NA cone's pupil):
  // G = 0, and no sampling derived from the cutoff applies.
  bool passes_light() const { return pupil_.outer > 0.0; }
  double blur_radius() const;  // m, geometric radius of the point image on the detector plane
  // Period (m, detector plane) of a lattice of point images whose diffraction tails put at most
  // `max_error` on the detector in total: the Parseval sum's aliases form such a lattice.
  double tail_period(double max_error) const;
  double aperture_area() const { return area_; }
  const AnnularPupil& pupil() const { return pupil_; }

 private:
  AnnularPupil pupil_{};
  double wavelength_, d_, r_d_, area_, z_;
};

}  // namespace lidar_overlap
