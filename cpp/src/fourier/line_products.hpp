// The loops over one line of a field that a propagation runs besides its transforms: the chirp products
// (the input and output chirps of A5 and of the chirp-z path, one loop for all) and the power sums of the
// validity checks. Internal header, not installed.
#pragma once

#include <cstddef>

#include "lidar_overlap/fourier/complex_buffer.hpp"

namespace lidar_overlap::detail {

// to[i] = from[i] (scale chirp[i]) for i < n, each product as std::complex computes it for finite values
// (without its NaN recovery, so that the loop vectorises; non-finite outputs are caught by the output's
// power). `from` may be `to`.
void chirp_product(const Complex* from, Complex scale, const Complex* chirp, Complex* to,
                   std::size_t n);

// sum |v_j|^2 over count values, in four interleaved partial sums (one dependent add per four doubles);
// the order is fixed, so the bits are.
double power(const Complex* v, std::size_t count);

}  // namespace lidar_overlap::detail
