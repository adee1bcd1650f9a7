// Two-dimensional DFT to an arbitrary output sampling (the "matrix Fourier transform"), computed with
// Bluestein's chirp-z algorithm on FFTW plans: O(L log L) per row, L >= n + m - 1, instead of O(n m).
//   out[my, mx] = sum_{ny, nx} in[ny, nx] exp(-2 pi i alpha ((mx - m/2)(nx - n/2) + (my - m/2)(ny - n/2)))
// With alpha = 1/n it is the centred DFT; a Fresnel or Fraunhofer integral to output spacing dx2 from
// input spacing dx over a distance z uses alpha = dx dx2 / (lambda z).
#pragma once

#include <cstddef>

#include "fourier/fft.hpp"

namespace lidar_overlap {

// `in` is n x n (n even), the result m x m (m even).
ComplexBuffer scaled_dft2d(const ComplexBuffer& in, std::size_t n, std::size_t m, double alpha);

}  // namespace lidar_overlap
