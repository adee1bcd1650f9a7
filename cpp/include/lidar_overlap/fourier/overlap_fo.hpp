// Fourier-optics overlap function G(z) (paper Appendix C). The transmitted field is propagated to each
// range (C1-C2) with lidar_overlap/fourier/propagate.hpp; every scatterer images through the receiver's pupil
// (aperture, obstruction shadow, lens, defocus, NA cone) onto the detector plane (C3-C6). Scatterers are
// mutually incoherent and the receiver is shift-invariant (the image of P is the image of the on-axis
// point moved to -P d/z), so G is the irradiance-weighted mean of (PSF (x) detector disc), computed as
// one sum over spatial frequencies: G = sum OTF(q) disc^(q) E^*(q d/z) phase / (pi R^2 E(0)).
// Shift invariance neglects the move of the obstruction's shadow (-P z_obs/(z - z_obs)) and of the NA
// cone (P/(z k)) across the pupil with the scatterer: both are far below the pupil scale for lidar beams.
#pragma once

#include <cstddef>
#include <vector>

#include "lidar_overlap/core/system.hpp"
#include "lidar_overlap/fourier/propagate.hpp"

namespace lidar_overlap {

struct FoOptions {
  std::size_t beam_grid = 256;  // samples per side of the TEM00 field (Gaussian beams only)
  double beam_window = 10.0;    // its window, in waist radii (10: +-5 w0)
  std::size_t max_spectrum_grid =
      4096;         // cap on the zero-padded beam spectrum (near-range defocus)
  int threads = 0;  // OpenMP threads across ranges; 0: all cores, per call. Callers that run
                    // calls from several threads pass 1 (or their share): core/limits.hpp
};

struct FoOverlap {
  std::vector<double> overlap;                  // G(z)
  std::vector<PropagationReport> beam_reports;  // the transmitted field's propagation to each range
  std::vector<std::size_t> spectrum_grid;       // padded spectrum size used at each range
};

// A diffraction-limited Gaussian beam is sampled (beam_grid, beam_window) and propagated to each range.
// A divergence above lambda / (pi w0) (M^2 > 1) is taken as a Gaussian Schell-model beam, whose
// irradiance is Gaussian with w(z)^2 = w0^2 + (theta z)^2 at every range: that irradiance is sampled
// directly (the receiver keeps full diffraction). Throws std::invalid_argument for the linear width
// law, a divergence below the diffraction limit, or a range that needs more than max_spectrum_grid.
FoOverlap overlap_fo(const LidarSystem& system, const std::vector<double>& ranges,
                     const FoOptions& options = {});

// The same for any transmitted field at z = 0 (flat-top, annular, vortex, ...), centred on the beam axis;
// system.beam gives its pointing (offset, tilt) only. The field must have the system's wavelength.
FoOverlap overlap_fo(const LidarSystem& system, const std::vector<double>& ranges,
                     const Field& transmitted, const FoOptions& options = {});

double emitter_coupling_fo(const LidarSystem& system, double z, Vec2 position);

}  // namespace lidar_overlap
