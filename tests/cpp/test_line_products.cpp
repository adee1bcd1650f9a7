// The propagation's line loops (chirp products, power sums, and both fused) give the bits of the plain
// double arithmetic written out here, the same operations in the same order (no reordering, no contraction
// into FMA: the results' bits in every process rest on it), on random values of wide magnitude, for lengths
// that leave every remainder of the vectorised loops, in place and out of place. Magnitudes from 1e-60 to
// 1e60: finite products and squares (NaN payloads may legitimately differ with the order of an addition's
// operands).
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

// Four partial sums over the doubles (lane j % 4), the rest into the first, then paired.
double fixed_order_power(const Complex* v, std::size_t n) {
  const double* d = reinterpret_cast<const double*>(v);
  double lane[4] = {0.0, 0.0, 0.0, 0.0};
  std::size_t j = 0;
  for (; j + 4 <= 2 * n; j += 4)
    for (int k = 0; k < 4; ++k) lane[k] += d[j + k] * d[j + k];
  for (; j < 2 * n; ++j) lane[0] += d[j] * d[j];
  return (lane[0] + lane[1]) + (lane[2] + lane[3]);
}
}  // namespace

int main() {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> decades(-60.0, 60.0);
  auto value = [&] { return Complex{g(rng), g(rng)} * std::pow(10.0, decades(rng)); };
  for (std::size_t n : {1, 2, 3, 5, 8, 13, 24, 64, 255, 1024}) {
    std::vector<Complex> from(n), out(n), expected(n);
    std::vector<double> re(n), im(n);
    for (std::size_t i = 0; i < n; ++i) {
      from[i] = value();
      re[i] = std::cos(g(rng));
      im[i] = std::sin(g(rng));
    }
    const Complex scale = value();
    for (std::size_t i = 0; i < n; ++i) {  // (scale chirp) first, then from times it
      const double pr = scale.real() * re[i] - scale.imag() * im[i];
      const double pi = scale.real() * im[i] + scale.imag() * re[i];
      expected[i] = {from[i].real() * pr - from[i].imag() * pi,
                     from[i].real() * pi + from[i].imag() * pr};
    }
    const std::string at = ", n = " + std::to_string(n);
    detail::chirp_product(from.data(), scale, re.data(), im.data(), out.data(), n);
    test::that("chirp product" + at + ": the bits of plain arithmetic",
               same_bits(out.data(), expected.data(), n * sizeof(Complex)));
    std::vector<Complex> in_place = from;
    detail::chirp_product(in_place.data(), scale, re.data(), im.data(), in_place.data(), n);
    test::that("chirp product in place" + at,
               same_bits(in_place.data(), expected.data(), n * sizeof(Complex)));

    const double sum = fixed_order_power(from.data(), n), got = detail::power(from.data(), n);
    test::that("power" + at + ": the bits of the fixed-order sum",
               same_bits(&got, &sum, sizeof(double)));

    // Fused: every border the checks use (n / 16, at least 1), odd ones and half the line, in place or not,
    // with and without the squares.
    for (std::size_t border :
         {std::size_t{1}, std::size_t{2}, std::max<std::size_t>(1, n / 16), n / 2}) {
      if (border == 0 || 2 * border > n) continue;
      const double total = fixed_order_power(expected.data(), n),
                   ends = fixed_order_power(expected.data(), border) +
                          fixed_order_power(expected.data() + n - border, border);
      for (bool same : {false, true}) {
        std::vector<Complex> to = same ? from : std::vector<Complex>(n);
        std::vector<double> squares(n);
        const detail::LinePower p =
            detail::chirp_product_power(same ? to.data() : from.data(), scale, re.data(), im.data(),
                                        to.data(), n, border, squares.data());
        const std::string case_ =
            at + ", border " + std::to_string(border) + (same ? ", in place" : "");
        test::that("fused product" + case_,
                   same_bits(to.data(), expected.data(), n * sizeof(Complex)));
        test::that("fused total power" + case_, same_bits(&p.total, &total, sizeof(double)));
        test::that("fused end power" + case_, same_bits(&p.ends, &ends, sizeof(double)));
        bool squares_ok = true;
        for (std::size_t i = 0; i < n; ++i) {
          const double s =
              expected[i].real() * expected[i].real() + expected[i].imag() * expected[i].imag();
          squares_ok = squares_ok && same_bits(&squares[i], &s, sizeof(double));
        }
        test::that("fused squares" + case_, squares_ok);
        const detail::LinePower q = detail::chirp_product_power(
            from.data(), scale, re.data(), im.data(), out.data(), n, border, nullptr);
        test::that("fused without squares" + case_, same_bits(&q.total, &total, sizeof(double)) &&
                                                        same_bits(&q.ends, &ends, sizeof(double)));
      }
    }
  }
  // The sum is the power: |3 + 4i|^2 + |1|^2 = 26 exactly.
  const std::vector<Complex> known{{3.0, 4.0}, {1.0, 0.0}};
  test::near("power of 3 + 4i and 1", detail::power(known.data(), known.size()), 26.0, 0.0);
  return test::report("test_line_products");
}
