// The turbulent FO path's coupling map of one range (internal header, not installed).
#pragma once

#include <cstddef>
#include <vector>

#include "lidar_overlap/core/system.hpp"
#include "lidar_overlap/fourier/field.hpp"
#include "fourier/fft.hpp"
#include "fourier/fo_receiver.hpp"

namespace lidar_overlap::detail {

// G at one range as a weighted mean of the realisation's irradiance: G = sum E m / sum E. The map m is
// the Parseval sum of overlap_from_irradiance (overlap_fo.cpp) moved to the beam plane: there G =
// sum_f T(f) Re[P(f) conj(FFT E)(f)] df^2 / (to_image^2 A E(0)) over the np x np padded grid, and as E is
// real, sum_f T P conj(FFT E) = sum_x E(x) Re BFFT[T P](x). m depends on the receiver, not on the
// atmosphere: made once per range, it leaves each realisation one pass over its n x n irradiance, with
// the same aliasing period (np dx) as the direct sum.
//
// BFFT[T P] is wanted on the beam's n x n window only, and it is real but for the Nyquist terms: T is even
// in kx and ky, P = Px(kx) Py(ky) Hermitian per axis. Along x, for each |ky| <= k_max (T = 0 beyond),
// R(|ky|, x) = sum_kx T Px e^(2 pi i kx x / np) over kx != np/2 is real and the same for ky and -ky: two
// rows |ky| share one complex transform (as the real and imaginary parts of its input). Along y, m(x, y)
// = Re sum_ky Py(ky) R(|ky|, x) e^(2 pi i ky y / np) has Hermitian coefficients but at ky = np/2, where only
// Re Py(np/2) adds to the real part: two window columns share one transform. The Nyquist column kx = np/2
// (nonzero when q_max reaches it) is a separable term of its own, Re[Px(np/2) (-1)^x S(y)], S the 1-D
// transform of Py T(np/2, |ky|). A quarter of the row transforms and half of the column ones of the
// direct 2-D transform, the same map to rounding.
class CouplingMap {
 public:
  static constexpr double kMapTable = 1 << 22;  // values of T tabled per map (32 MB)
  // Bytes a thread needs to make the map of an np grid: T's table (or two rows), R, and a block of transforms.
  static double workspace(std::size_t n, std::size_t np) {
    const double width = 0.5 * double(np) + 1.0;
    return 8.0 * std::min(kMapTable, width * width) + 8.0 * double(n) * width +
           16.0 * double(kFftBlock) * double(np);
  }
  CouplingMap(const LidarSystem& system, const FoReceiver& rx, double z, double dx, std::size_t n,
              std::size_t np);

  // G from the per-column sums an arrival leaves (scaled_step.hpp, map_column_sums), added in column order.
  double overlap(const std::vector<double>& column_sums) const {
    double e = 0.0, em = 0.0;
    for (std::size_t ix = 0; ix < n_; ++ix) e += column_sums[2 * ix], em += column_sums[2 * ix + 1];
    return em / e;
  }
  // The map by columns: values()[ix * n + iy] is m at (x_ix, y_iy).
  const double* values() const { return map_.data(); }

 private:
  std::size_t n_;
  std::vector<double> map_;
};

}  // namespace lidar_overlap::detail
