// exp(i phase) of a phase screen's samples, the turbulent FO path's most frequent transcendental call (one per
// sample per screen per realisation): libm's cos and sin cost ~30 ns a sample there, this ~6 ns. Cody-Waite
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

// exp(i phase) for phase in rad.
inline Complex phasor(double phase) {
  if (!(std::abs(phase) <= kPhasorReach)) return {std::cos(phase), std::sin(phase)};
  constexpr double two_over_pi = 0.63661977236758134308, magic = 6755399441055744.0;  // 1.5 x 2^52: rounds
  constexpr double p1 = 1.57079632673412561417e+00, p2 = 6.07710050630396597660e-11, p3 = 2.02226624871116645580e-21;
  constexpr double s1 = -1.66666666666666324348e-01, s2 = 8.33333333332248946124e-03, s3 = -1.98412698298579493134e-04,
                   s4 = 2.75573137070700676789e-06, s5 = -2.50507602534068634195e-08, s6 = 1.58969099521155010221e-10;
  constexpr double c1 = 4.16666666666666019037e-02, c2 = -1.38888888888741095749e-03, c3 = 2.48015872894767294178e-05,
                   c4 = -2.75573143513906633035e-07, c5 = 2.08757232129817482790e-09, c6 = -1.13596475577881948265e-11;
  const double t = phase * two_over_pi + magic;
  std::uint64_t bits;
  std::memcpy(&bits, &t, sizeof bits);  // the low bits of t are k, the nearest integer to phase / (pi/2)
  const double k = t - magic;
  const double r = ((phase - k * p1) - k * p2) - k * p3, z = r * r;
  const double sin_r = r + r * z * (s1 + z * (s2 + z * (s3 + z * (s4 + z * (s5 + z * s6)))));
  const double half_z = 0.5 * z, w = 1.0 - half_z;
  const double cos_r = w + (((1.0 - w) - half_z) + z * z * (c1 + z * (c2 + z * (c3 + z * (c4 + z * (c5 + z * c6))))));
  const unsigned quadrant = static_cast<unsigned>(bits & 3);
  const double s = quadrant & 1 ? cos_r : sin_r, c = quadrant & 1 ? sin_r : cos_r;
  return {quadrant == 1 || quadrant == 2 ? -c : c, quadrant & 2 ? -s : s};
}

}  // namespace lidar_overlap::detail
