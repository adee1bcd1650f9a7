// What the FFT tests compare transforms with: their round-off tolerance, pseudo-random input and the DFT as
// a direct sum.
#pragma once

#include <complex>
#include <cstddef>

#include "core/constants.hpp"
#include "lidar_overlap/fourier/complex_buffer.hpp"

namespace test {

// Round-off of an n-point FFT relative to the largest value: ~1e-16 log2(n); 1e-12 leaves room.
inline constexpr double kRoundOff = 1e-12;

// `size` values with parts uniform in [-0.5, 0.5), the same on every run.
inline lidar_overlap::ComplexBuffer pseudo_random(std::size_t size) {
  lidar_overlap::ComplexBuffer v(size);
  unsigned long long s = 12345;
  for (lidar_overlap::Complex& x : v) {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    const double a = static_cast<double>(s >> 11) / 9007199254740992.0;
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    x = {a - 0.5, static_cast<double>(s >> 11) / 9007199254740992.0 - 0.5};
  }
  return v;
}

// Coefficient k of the DFT of in[0 .. length): the sum of in[j] exp(sign 2 pi i j k / length).
inline lidar_overlap::Complex direct_dft(const lidar_overlap::Complex* in, std::size_t length,
                                         std::size_t k, int sign) {
  lidar_overlap::Complex sum{};
  for (std::size_t j = 0; j < length; ++j)
    sum += in[j] * std::polar(1.0, sign * 2.0 * lidar_overlap::kPi * double(j * k % length) /
                                       double(length));
  return sum;
}

}  // namespace test
