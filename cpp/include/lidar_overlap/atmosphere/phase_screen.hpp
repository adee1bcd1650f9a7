// Random phase screens of atmospheric turbulence by the FFT method with subharmonics (Lane et al.,
// Waves in Random Media 1992; the ft_sh_phase_screen of Schmidt, "Numerical Simulation of Optical Wave
// Propagation with Examples in MATLAB" (SPIE, 2010), Listing 9.3). Modified von Karman phase PSD in
// cycles/m: Phi(f) = c r0^(-5/3) exp(-(f / fm)^2) / (f^2 + f0^2)^(11/6), fm = 5.92 / (2 pi l0),
// f0 = 1 / L0; c = 0.0229 (Schmidt's 0.023 rounded), the value for which the Kolmogorov structure
// function is exactly 6.88 (r / r0)^(5/3).
//
// High frequencies: complex white noise filtered by sqrt(Phi) df on the n x n FFT grid (df = 1 / (n dx),
// zero at f = 0), inverse FFT. Low frequencies: 3 levels of 3 x 3 subharmonics at df / 3^p (p = 1..3),
// their mean over the grid removed. The real and imaginary parts of the complex sum are two independent
// screens, so each FFT gives the pair (2 m, 2 m + 1) of the stream.
//
// Weights of the cells around f = 0. Schmidt's listing gives every cell the variance Phi(centre) x area.
// Near f = 0 the PSD varies by orders of magnitude across a cell, and that under-weights the low
// frequencies: for Kolmogorov on a 256^2 grid the mean structure function falls 12 % short of
// 6.88 (r / r0)^(5/3) at 4 samples and 29 % at n / 4 (and the part of the spectrum inside the last
// subharmonic cell, whose share only falls as 3^(-levels/3), is lost). SubharmonicWeights::tilt_matched
// (the default) keeps the cell centres and the 3 x 3 structure but gives each of these cells (the FFT
// grid's 8 neighbours of f = 0 and every subharmonic) the phase-gradient variance of its whole cell,
// int_cell Phi |f|^2 d^2f / |f_centre|^2, and adds the leftover centre cell's gradient variance to the
// last level: below 1 / D the screen is essentially a tilt, and that is what it then carries in full.
// Its mean structure function is within 2 % of 6.88 (r / r0)^(5/3) from 4 samples to n / 4
// (tests/cpp/test_phase_screen.cpp); SubharmonicWeights::schmidt reproduces the listing.
//
// Reproducible and thread-safe: screen `index` of the stream `seed` depends only on (seed, index). The
// pair index / 2 seeds a xoshiro256++ generator with a splitmix64 hash of (seed, index / 2), whose 64-bit
// outputs (fixed by its definition) are turned into normal deviates here by a ziggurat, not by
// std::normal_distribution, which differs between standard libraries. Even indices are the real part,
// odd ones the imaginary part. The same (seed, index) gives the same screen in any call order and from
// any thread, bit for bit (on one platform: libm and FFTW round as they do).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "lidar_overlap/fourier/field.hpp"

namespace lidar_overlap {

enum class SubharmonicWeights { tilt_matched, schmidt };

class PhaseScreenGenerator {
 public:
  // n x n samples (n even >= 8) of `spacing` (m); Fried parameter `r0` (m; infinity gives zero
  // screens), outer scale (m; infinity: Kolmogorov), inner scale (m; 0: none).
  PhaseScreenGenerator(std::size_t n, double spacing, double r0,
                       double outer_scale = std::numeric_limits<double>::infinity(),
                       double inner_scale = 0.0,
                       SubharmonicWeights weights = SubharmonicWeights::tilt_matched);

  // Screen `index` of the stream `seed`: rad, n x n row-major (screen[iy * n + ix]), sample (ix, iy) at
  // the Field coordinates x = (ix - n/2) spacing, y = (iy - n/2) spacing.
  std::vector<double> generate(std::uint64_t seed, std::size_t index) const;

  // Screens 2 pair and 2 pair + 1 from one FFT (half the cost of two generate calls).
  std::array<std::vector<double>, 2> generate_pair(std::uint64_t seed, std::size_t pair) const;
  // The same pair into `out`, with `spectrum` as the transform's workspace: both keep their storage from call to
  // call (sized to n x n on first use), so that a caller making many pairs allocates and zeroes them once.
  void generate_pair(std::uint64_t seed, std::size_t pair, std::array<std::vector<double>, 2>& out,
                     ComplexBuffer& spectrum) const;

  // Phase PSD Phi(f) (rad^2 m^2) at spatial frequency f (cycles/m).
  double psd(double f) const;

  std::size_t n() const { return n_; }
  double spacing() const { return spacing_; }          // m
  double r0() const { return r0_; }                    // m
  double outer_scale() const { return outer_scale_; }  // m
  double inner_scale() const { return inner_scale_; }  // m
  SubharmonicWeights weights() const { return weights_; }

 private:
  std::size_t n_;
  double spacing_, r0_, outer_scale_, inner_scale_;
  SubharmonicWeights weights_;
  std::vector<double>
      amplitude_;  // sqrt(Phi) df on |fx|, |fy| in 0..n/2: (n/2 + 1)^2, [|ky| (n/2+1) + |kx|]
  std::array<double, 27>
      sub_amplitude_;  // sqrt(Phi) df_p of subharmonic (p, b, a) at [9 p + 3 (b + 1) + (a + 1)]
  std::array<std::vector<double>, 3> sub_cos_,
      sub_sin_;                        // exp(i 2 pi df_p x_i) per axis, per level
  std::array<Complex, 3> sub_mean_{};  // their means over the grid
};

// Multiplies `field` by exp(i screen) (screen in rad, n x n like the field).
void apply_phase_screen(Field& field, const std::vector<double>& screen);

}  // namespace lidar_overlap
