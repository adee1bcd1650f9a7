// exp(i phase) of a phase screen's samples, the turbulent FO path's most frequent transcendental call (one per
// sample per screen per realisation): libm's cos and sin cost ~30 ns a sample there, phasors ~4-8 ns (random
// quadrants: a branch on the quadrant would mispredict half the time, ~20 ns). Cody-Waite
// reduction by pi/2 in three parts (exact k pi/2 for |k| < 2^20), fdlibm's kernels on [-pi/4, pi/4]: within
// 2 ulp of libm's, the same bits on any thread. Beyond kPhasorReach (no screen reaches it) libm is used.
// Internal header, not installed.
#pragma once

#include <cmath>
#include <cstdint>

#include "lidar_overlap/fourier/complex_buffer.hpp"

namespace lidar_overlap::detail {

inline constexpr double kPhasorReach =
    1e5;  // rad: |k| < 2^16, far inside the reduction's exact range

namespace phasor_kernel {
constexpr double two_over_pi = 0.63661977236758134308,
                 magic = 6755399441055744.0;  // 1.5 x 2^52: rounds
constexpr double p1 = 1.57079632673412561417e+00, p2 = 6.07710050630396597660e-11,
                 p3 = 2.02226624871116645580e-21;
constexpr double s1 = -1.66666666666666324348e-01, s2 = 8.33333333332248946124e-03,
                 s3 = -1.98412698298579493134e-04, s4 = 2.75573137070700676789e-06,
                 s5 = -2.50507602534068634195e-08, s6 = 1.58969099521155010221e-10;
constexpr double c1 = 4.16666666666666019037e-02, c2 = -1.38888888888741095749e-03,
                 c3 = 2.48015872894767294178e-05, c4 = -2.75573143513906633035e-07,
                 c5 = 2.08757232129817482790e-09, c6 = -1.13596475577881948265e-11;

// Lanes at a time (GCC and Clang vector extensions: SSE2 or AVX2 on x86-64, NEON on AArch64, scalar code
// elsewhere), the same IEEE operations in each lane, no fused multiply-adds.
using Doubles = double __attribute__((vector_size(16)));
using Words = std::uint64_t __attribute__((vector_size(16)));

// exp(i phase) for |phase| <= kPhasorReach, branch-free (k = round(phase / (pi/2)), exact there; the low bits
// of t are k mod 4, also for k < 0): the quadrant's swap and signs are bit masks.
template <class D, class W>
__attribute__((always_inline)) inline void reduced(D phase, D& re, D& im) {
  const D t = phase * two_over_pi + magic, k = t - magic;
  const W quadrant = __builtin_bit_cast(W, t) & 3;
  const D r = ((phase - k * p1) - k * p2) - k * p3, z = r * r;
  const D sin_r = r + r * z * (s1 + z * (s2 + z * (s3 + z * (s4 + z * (s5 + z * s6)))));
  const D half_z = 0.5 * z, w = 1.0 - half_z;
  const D cos_r = w + (((1.0 - w) - half_z) +
                       z * z * (c1 + z * (c2 + z * (c3 + z * (c4 + z * (c5 + z * c6))))));
  const W swap = 0 - (quadrant & 1), sb = __builtin_bit_cast(W, sin_r),
          cb = __builtin_bit_cast(W, cos_r);
  const W s = (sb & ~swap) | (cb & swap), c = (cb & ~swap) | (sb & swap);
  const W re_bits = c ^ (((quadrant + 1) & 2) << 62),
          im_bits = s ^ ((quadrant & 2) << 62);  // quadrants 1, 2; 2, 3
  re = __builtin_bit_cast(D, re_bits);
  im = __builtin_bit_cast(D, im_bits);
}
}  // namespace phasor_kernel

// exp(i phase) for phase in rad.
inline Complex phasor(double phase) {
  if (!(std::abs(phase) <= kPhasorReach)) return {std::cos(phase), std::sin(phase)};
  using phasor_kernel::Doubles;
  Doubles re, im;
  phasor_kernel::reduced<Doubles, phasor_kernel::Words>(Doubles{phase, 0.0}, re, im);
  return {re[0], im[0]};
}

// out[j] = phasor(phase[j]) for j < count, the same bits, several at a time (phasor.cpp: four lanes where the
// processor has AVX2, else two); phases beyond kPhasorReach, or NaN, are mended one by one.
void phasors(const double* phase, Complex* out, std::size_t count);

}  // namespace lidar_overlap::detail
