// Fourier-optics overlap of a receiver with wavefront aberrations (paper Section 3, step 5; Appendix C with
// Zernike terms in the pupil). The pupil P(a) exp(i psi |a|^2 + 2 pi i W(a) / lambda) has no closed-form OTF
// once W is not a defocus, so at each range it is sampled and its autocorrelation (the OTF at pupil shifts)
// computed by two FFTs. With scatterers incoherent and the image shift-invariant (Zernike terms are the same
// for every scatterer), G is the Parseval sum over that OTF times the spectrum of the Gaussian beam image seen
// through the detector disc, exp(-pi^2 w_i^2 q^2 / 2) disc^(q) exp(-2 pi i q.s):
//   G = G_0 + sum_q [OTF_W(q) - OTF_0(q)] K^(q) dq^2 / (pi R^2),
// where G_0 is the aberration-free overlap from the exact radial integral (fourier/overlap_fo_radial.hpp) and the
// sum takes the difference of the sampled aberrated and aberration-free OTFs: the sampling's own errors (edge
// pixels, periodic copies of the point image) are nearly equal in both and cancel (measured: ~5x smaller).
// The pupil spacing lambda d / L puts the copies L apart, beyond the point image plus the beam image and the
// detector, plus the distance at which their diffraction tails put tail_error on G. Near ranges, where the
// defocus blur is many Airy radii, need transforms beyond max_grid: there ray tracing is exact.
#pragma once

#include <cstddef>
#include <vector>

#include "lidar_overlap/pupil/aberrations.hpp"
#include "lidar_overlap/core/system.hpp"
#include "lidar_overlap/fourier/field.hpp"

namespace lidar_overlap {

struct FoAberratedOptions {
  std::size_t max_grid = 4096;  // cap on the pupil transform's size per side
  double tail_error =
      1e-4;         // sets the alias period: the aliases' tails put this on G before they cancel
  int threads = 0;  // OpenMP threads across ranges; 0: all cores, per call. Callers that run
                    // calls from several threads pass 1 (or their share): core/limits.hpp
};

struct FoAberratedOverlap {
  std::vector<double> overlap;    // G(z)
  std::vector<std::size_t> grid;  // transform size used at each range
};

// Gaussian-irradiance beams (TEM00 and the M^2 > 1 Schell model, width law "gaussian"). Throws
// std::invalid_argument for field-dependent Seidel terms (they break shift invariance: trace rays),
// for an invalid system or range, and for a range that needs more than max_grid, naming it.
FoAberratedOverlap overlap_fo_aberrated(const LidarSystem& system, const Aberrations& aberrations,
                                        const std::vector<double>& ranges,
                                        const FoAberratedOptions& options = {});

// The point image (complex amplitude, detector plane) of an on-axis scatterer at range z (m): n x n samples at
// `spacing` (m), normalised so that sum |h|^2 spacing^2 is the fraction of the full aperture's power the pupil
// passes. The pupil is sampled at lambda d / (n spacing), which must resolve it: spacing <= lambda d / D.
Field point_image(const LidarSystem& system, const Aberrations& aberrations, double z,
                  std::size_t n, double spacing);

}  // namespace lidar_overlap
