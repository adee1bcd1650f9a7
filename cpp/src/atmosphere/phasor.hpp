// exp(i phase) of a phase screen's samples, the turbulent FO path's most frequent transcendental call (one per
// sample per screen per realisation): libm's cos and sin cost ~30 ns a sample there, phasors ~4-8 ns (random
// quadrants: a branch on the quadrant would mispredict half the time, ~20 ns). Cody-Waite
// reduction by pi/2 in three parts (exact k pi/2 for |k| < 2^20), fdlibm's kernels on [-pi/4, pi/4]: within
// 2 ulp of libm's, the same bits on any thread. Beyond kPhasorReach (no screen reaches it) libm is used.
// Internal header, not installed.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

#include "lidar_overlap/fourier/complex_buffer.hpp"

namespace lidar_overlap::detail {

inline constexpr double kPhasorReach = 1e5;  // rad: |k| < 2^16, far inside the reduction's exact range

namespace phasor_kernel {
constexpr double two_over_pi = 0.63661977236758134308, magic = 6755399441055744.0;  // 1.5 x 2^52: rounds
constexpr double p1 = 1.57079632673412561417e+00, p2 = 6.07710050630396597660e-11, p3 = 2.02226624871116645580e-21;
constexpr double s1 = -1.66666666666666324348e-01, s2 = 8.33333333332248946124e-03, s3 = -1.98412698298579493134e-04,
                 s4 = 2.75573137070700676789e-06, s5 = -2.50507602534068634195e-08, s6 = 1.58969099521155010221e-10;
constexpr double c1 = 4.16666666666666019037e-02, c2 = -1.38888888888741095749e-03, c3 = 2.48015872894767294178e-05,
                 c4 = -2.75573143513906633035e-07, c5 = 2.08757232129817482790e-09, c6 = -1.13596475577881948265e-11;

// Two lanes at a time (GCC and Clang vector extensions: SSE2 on x86-64, NEON on AArch64, scalar code
// elsewhere), the same IEEE operations in each lane.
using Doubles = double __attribute__((vector_size(16)));
using Words = std::uint64_t __attribute__((vector_size(16)));

// exp(i phase) for |phase| <= kPhasorReach, branch-free (k = round(phase / (pi/2)), exact there; the low bits
// of t are k mod 4, also for k < 0): the quadrant's swap and signs are bit masks.
inline void reduced(Doubles phase, Doubles& re, Doubles& im) {
  const Doubles t = phase * two_over_pi + magic, k = t - magic;
  const Words quadrant = __builtin_bit_cast(Words, t) & 3;
  const Doubles r = ((phase - k * p1) - k * p2) - k * p3, z = r * r;
  const Doubles sin_r = r + r * z * (s1 + z * (s2 + z * (s3 + z * (s4 + z * (s5 + z * s6)))));
  const Doubles half_z = 0.5 * z, w = 1.0 - half_z;
  const Doubles cos_r = w + (((1.0 - w) - half_z) + z * z * (c1 + z * (c2 + z * (c3 + z * (c4 + z * (c5 + z * c6))))));
  const Words swap = 0 - (quadrant & 1), sb = __builtin_bit_cast(Words, sin_r),
              cb = __builtin_bit_cast(Words, cos_r);
  const Words s = (sb & ~swap) | (cb & swap), c = (cb & ~swap) | (sb & swap);
  const Words re_bits = c ^ (((quadrant + 1) & 2) << 62), im_bits = s ^ ((quadrant & 2) << 62);  // quadrants 1, 2; 2, 3
  re = __builtin_bit_cast(Doubles, re_bits);
  im = __builtin_bit_cast(Doubles, im_bits);
}
}  // namespace phasor_kernel

// exp(i phase) for phase in rad.
inline Complex phasor(double phase) {
  if (!(std::abs(phase) <= kPhasorReach)) return {std::cos(phase), std::sin(phase)};
  phasor_kernel::Doubles re, im;
  phasor_kernel::reduced(phasor_kernel::Doubles{phase, 0.0}, re, im);
  return {re[0], im[0]};
}

// out[j] = phasor(phase[j]) for j < count, the same bits, two at a time (phases beyond kPhasorReach, or NaN,
// are mended afterwards one by one).
inline void phasors(const double* phase, Complex* out, std::size_t count) {
  using phasor_kernel::Doubles;
  auto inside = [](double x) { return std::abs(x) <= kPhasorReach ? x : 0.0; };
  std::size_t j = 0;
  for (; j + 1 < count; j += 2) {
    Doubles re, im;
    phasor_kernel::reduced(Doubles{inside(phase[j]), inside(phase[j + 1])}, re, im);
    out[j] = {re[0], im[0]};
    out[j + 1] = {re[1], im[1]};
  }
  if (j < count) out[j] = phasor(inside(phase[j]));
  bool far = false;
  for (std::size_t j = 0; j < count; ++j) far |= !(std::abs(phase[j]) <= kPhasorReach);
  if (far)
    for (std::size_t j = 0; j < count; ++j)
      if (!(std::abs(phase[j]) <= kPhasorReach)) out[j] = phasor(phase[j]);
}

}  // namespace lidar_overlap::detail
