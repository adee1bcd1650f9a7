// The propagation's line loops (chirp products, power sums) give the bits of the plain double arithmetic
// written out here, the same operations in the same order (no reordering, no contraction into FMA: the
// results' bits in every process rest on it), on random values of wide magnitude, for lengths that leave
// every remainder of the vectorised loops, in place and out of place. Magnitudes from 1e-60 to 1e60: finite
// products and squares (NaN payloads may legitimately differ with the order of an addition's operands).
#include <cstring>
#include <random>
#include <vector>

#include "check.hpp"
#include "fourier/line_products.hpp"

using namespace lidar_overlap;

namespace {
bool same_bits(const void* a, const void* b, std::size_t bytes) {
  return std::memcmp(a, b, bytes) == 0;
}
}  // namespace

int main() {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> decades(-60.0, 60.0);
  auto value = [&] { return Complex{g(rng), g(rng)} * std::pow(10.0, decades(rng)); };
  for (std::size_t n : {1, 2, 3, 5, 8, 13, 64, 255, 1024}) {
    std::vector<Complex> from(n), chirp(n), out(n), expected(n);
    for (std::size_t i = 0; i < n; ++i) {
      from[i] = value();
      chirp[i] = {std::cos(g(rng)), std::sin(g(rng))};
    }
    const Complex scale = value();
    for (std::size_t i = 0; i < n; ++i) {  // (scale chirp) first, then from times it
      const double pr = scale.real() * chirp[i].real() - scale.imag() * chirp[i].imag();
      const double pi = scale.real() * chirp[i].imag() + scale.imag() * chirp[i].real();
      expected[i] = {from[i].real() * pr - from[i].imag() * pi,
                     from[i].real() * pi + from[i].imag() * pr};
    }
    detail::chirp_product(from.data(), scale, chirp.data(), out.data(), n);
    test::that("chirp product, n = " + std::to_string(n) + ": the bits of plain arithmetic",
               same_bits(out.data(), expected.data(), n * sizeof(Complex)));
    std::vector<Complex> in_place = from;
    detail::chirp_product(in_place.data(), scale, chirp.data(), in_place.data(), n);
    test::that("chirp product in place, n = " + std::to_string(n),
               same_bits(in_place.data(), expected.data(), n * sizeof(Complex)));

    // Four partial sums over the doubles (lane j % 4), the rest into the first, then paired.
    const double* d = reinterpret_cast<const double*>(from.data());
    double lane[4] = {0.0, 0.0, 0.0, 0.0};
    std::size_t j = 0;
    for (; j + 4 <= 2 * n; j += 4)
      for (int k = 0; k < 4; ++k) lane[k] += d[j + k] * d[j + k];
    for (; j < 2 * n; ++j) lane[0] += d[j] * d[j];
    const double sum = (lane[0] + lane[1]) + (lane[2] + lane[3]),
                 got = detail::power(from.data(), n);
    test::that("power, n = " + std::to_string(n) + ": the bits of the fixed-order sum",
               same_bits(&got, &sum, sizeof(double)));
  }
  // The sum is the power: |3 + 4i|^2 + |1|^2 = 26 exactly.
  const std::vector<Complex> known{{3.0, 4.0}, {1.0, 0.0}};
  test::near("power of 3 + 4i and 1", detail::power(known.data(), known.size()), 26.0, 0.0);
  return test::report("test_line_products");
}
