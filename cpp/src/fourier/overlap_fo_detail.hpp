// Internal pieces of the 2-D Fourier-optics overlap shared by the paths that make the beam irradiance
// their own way (overlap_fo.cpp: propagated or Schell-model beams; overlap_turbulent.cpp: beams through
// phase screens). Not installed.
#pragma once

#include <cstddef>
#include <vector>

#include "lidar_overlap/fourier/field.hpp"
#include "fourier/fo_receiver.hpp"

namespace lidar_overlap::detail {

// How far a Fourier-optics G may stray outside [0, 1] before it is an error rather than round-off: 100x the
// 2-D path's nominal accuracy (the radial path is far more accurate, the aberrated one 5e-6).
inline constexpr double kFoOverlapSlack = 1e-4;

// G at range z (m) from the beam field at_z in the beam's own frame (centred on system.beam.center(z)):
// Parseval's sum over its irradiance spectrum zero-padded to np x np (see overlap_fo.hpp).
double overlap_from_irradiance(const LidarSystem& system, const FoReceiver& rx, const Field& at_z,
                               double z, std::size_t np);

// The phase of the Parseval sum per axis, exp(2 pi i f shift) (-1)^k at the frequencies f = df k (k signed,
// k >= np/2 taken as k - np) of an np-point padded grid: the beam image shifted by `shift` (m, beam plane)
// against the detector centre, and the padded grid's origin at np/2.
struct ShiftPhases {
  ShiftPhases(std::size_t np, double df, Vec2 shift);
  std::vector<Complex> x, y;
};

// The padded spectrum size for a beam of grid `spacing` (m) and n samples whose power (all but 1e-7) lies
// within `radius_bound` (m), the aliases' diffraction tails kept below `tail_error` of G; throws naming
// ranges[range_index] above max_grid; 0 when no light reaches the detector plane (G = 0). The size is a
// power of two, or with `any_fast_size` the least even 2^a 3^b 5^c 7^d that holds the alias period (up to
// half the work per axis: the period only has to be reached, and FFTW transforms these sizes as fast).
std::size_t spectrum_grid(const LidarSystem& system, const FoReceiver& rx, double z, double spacing,
                          double radius_bound, std::size_t n, std::size_t max_grid,
                          std::size_t range_index, double tail_error = 1e-6,
                          bool any_fast_size = false);

// Least even m >= n of the form 2^a 3^b 5^c 7^d.
std::size_t even_fast_fft_size(std::size_t n);

}  // namespace lidar_overlap::detail
