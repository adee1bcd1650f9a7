// The loops over one line of a field that a propagation runs besides its transforms: the chirp products
// (the input and output chirps of A5 and of the chirp-z path, one loop for all) and the power sums of the
// validity checks, fused into one loop where the sums allow. Chirps come split into their real and
// imaginary parts (re[0..n), im[0..n)): two values of a product loop then need no shuffle of the chirp.
// Internal header, not installed.
#pragma once

#include <cstddef>

#include "lidar_overlap/fourier/complex_buffer.hpp"

namespace lidar_overlap::detail {

// to[i] = from[i] (scale (re[i] + i im[i])) for i < n, each product as std::complex computes it for finite
// values (without its NaN recovery, so that the loop vectorises; non-finite outputs are caught by the
// output's power). `from` may be `to`.
void chirp_product(const Complex* from, Complex scale, const double* re, const double* im,
                   Complex* to, std::size_t n);

// sum |v_j|^2 over count values, in four interleaved partial sums (one dependent add per four doubles);
// the order is fixed, so the bits are.
double power(const Complex* v, std::size_t count);

// The power of a line and of its two ends: total = power(v, n), ends = power(v, border) + power(v + n -
// border, border).
struct LinePower {
  double total, ends;
};

// chirp_product(from, scale, re, im, to, n), the LinePower of `to` (border <= n / 2) and, unless null,
// squares[i] = |to[i]|^2: the same bits as those calls, in one loop that sums the squares while the
// products are still in registers.
LinePower chirp_product_power(const Complex* from, Complex scale, const double* re,
                              const double* im, Complex* to, std::size_t n, std::size_t border,
                              double* squares);

}  // namespace lidar_overlap::detail
