// Fourier-optics overlap function G(z) (paper Appendix C). The transmitted field is propagated to each
// range (C1-C2) with lidar_overlap/propagate.hpp; every scatterer images through the receiver's pupil
// (aperture, obstruction shadow, lens, defocus, NA cone) onto the detector plane (C3-C6). Scatterers are
// mutually incoherent and the receiver is shift-invariant (the image of P is the image of the on-axis
// point moved to -P d/z), so G is the irradiance-weighted mean of (PSF (x) detector disc), computed as
// one sum over spatial frequencies: G = sum OTF(q) disc^(q) E^*(q d/z) phase / (pi R^2 E(0)).
// Shift invariance neglects the move of the obstruction's shadow (-P z_obs/(z - z_obs)) and of the NA
// cone (P/(z k)) across the pupil with the scatterer: both are far below the pupil scale for lidar beams.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "lidar_overlap/otf.hpp"
#include "lidar_overlap/propagate.hpp"
#include "lidar_overlap/system.hpp"

namespace lidar_overlap {

struct FoOptions {
  std::size_t beam_grid = 256;          // samples per side of the TEM00 field (Gaussian beams only)
  double beam_window = 10.0;            // its window, in waist radii (10: +-5 w0)
  std::size_t max_spectrum_grid = 4096; // cap on the zero-padded beam spectrum (near-range defocus)
  int threads = 0;                      // OpenMP threads across ranges; 0: all cores
};

struct FoOverlap {
  std::vector<double> overlap;                    // G(z)
  std::vector<PropagationReport> beam_reports;    // the transmitted field's propagation to each range
  std::vector<std::size_t> spectrum_grid;         // padded spectrum size used at each range
};

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

// A diffraction-limited Gaussian beam is sampled (beam_grid, beam_window) and propagated to each range.
// A divergence above lambda / (pi w0) (M^2 > 1) is taken as a Gaussian Schell-model beam, whose
// irradiance is Gaussian with w(z)^2 = w0^2 + (theta z)^2 at every range: that irradiance is sampled
// directly (the receiver keeps full diffraction). Throws std::invalid_argument for the linear width
// law, a divergence below the diffraction limit, or a range that needs more than max_spectrum_grid.
FoOverlap overlap_fo(const LidarSystem& system, const std::vector<double>& ranges, const FoOptions& options = {});

// The same for any transmitted field at z = 0 (flat-top, annular, vortex, ...), centred on the beam axis;
// system.beam gives its pointing (offset, tilt) only. The field must have the system's wavelength.
FoOverlap overlap_fo(const LidarSystem& system, const std::vector<double>& ranges, const Field& transmitted,
                     const FoOptions& options = {});

double emitter_coupling_fo(const LidarSystem& system, double z, Vec2 position);

}  // namespace lidar_overlap
