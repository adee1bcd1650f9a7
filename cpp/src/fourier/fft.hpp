// FFTW plans made once per shape and reused (plan/execute). Planning is serialised behind one mutex,
// FFTW's threads are initialised once, and execution on other buffers of the same shape uses FFTW's
// thread-safe new-array interface, so plans may be shared by concurrent calls. Internal header, not installed.
#pragma once

#include <algorithm>
#include <cstddef>

#include "lidar_overlap/fourier/complex_buffer.hpp"

namespace lidar_overlap {

enum class FftDirection { forward, backward };  // exp(-2 pi i ...) and exp(+2 pi i ...), unnormalised

// How hard FFTW plans: `measure` times candidate algorithms once per shape (worth it for shapes used many
// times); `estimate` plans at once, for large shapes that change from call to call. Inside an OpenMP region
// (the library's loops over ranges) every plan is `estimate` and single-threaded, so that the overlap paths
// give the same bits for any thread count and in any process.
enum class FftPlanning { measure, estimate };

// In-place 2-D transform of an n x n row-major array.
void fft2d(ComplexBuffer& data, std::size_t n, FftDirection direction, FftPlanning planning = FftPlanning::measure);

// In-place 1-D transforms of `rows` contiguous rows of `length` each.
void fft_rows(ComplexBuffer& data, std::size_t rows, std::size_t length, FftDirection direction);

// Smallest power of two >= v: the sizes FFTW transforms fastest (2^63 for any v beyond it).
inline std::size_t next_power_of_two(std::size_t v) {
  std::size_t p = 1;
  while (p < v && p < (std::size_t{1} << 63)) p <<= 1;
  return p;
}

// Smallest n' >= n of the form 2^a 3^b 5^c 7^d: sizes FFTW also transforms fast, closer to n than a power
// of two (for one-off transforms, where a power of two would only add work).
// Sizes beyond 2^32, which no grid budget allows, are returned as they are (callers check them).
inline std::size_t fast_fft_size(std::size_t n) {
  if (n > (std::size_t{1} << 32)) return n;
  for (std::size_t m = std::max<std::size_t>(n, 2);; ++m) {
    std::size_t r = m;
    for (std::size_t p : {2, 3, 5, 7})
      while (r % p == 0) r /= p;
    if (r == 1) return m;
  }
}

}  // namespace lidar_overlap
