// What a propagation's validity checks need of a field (its Extent), gathered line by line while the passes
// of a propagation hold each line in cache (ExtentSums). Internal header, not installed.
#pragma once

#include <cstddef>
#include <vector>

#include "fourier/line_products.hpp"
#include "lidar_overlap/fourier/complex_buffer.hpp"

namespace lidar_overlap::detail {

// Total power, power in the outer n/16 of the window, and the power per squared radius about the optical
// axis (bins of n/8 samples^2: no square root per sample, and a quarter sample of radius at r = n/4), taken
// on every other row and column.
struct Extent {
  double total = 0.0, border = 0.0;
  std::size_t n;
  std::vector<double> radial;
  explicit Extent(std::size_t n_) : n(n_), radial(4 * n_ + 2, 0.0) {}
  double edge_fraction() const { return total > 0.0 ? border / total : 0.0; }
  // Radius (m) holding `fraction` of the (sampled) radial profile's power, for samples of spacing dx.
  double radius(double fraction, double dx) const;
};

// Gathers an Extent from the lines (rows, or columns: the window is square and the checks symmetric) of a
// field as a pass finishes each of them, on any thread and in any order. Totals are kept per line and
// added in line order, so they are the same bits for any schedule; the radial profile is kept per thread
// (it only places the extent on its bin edges).
class ExtentSums {
 public:
  // For an n x n field whose lines are added by the members of a team of up to `threads`
  // (core/team.hpp); the radial profile only when `radial`.
  ExtentSums(std::size_t n, int threads, bool radial);

  // Line i holding its final values v[0..n).
  void add(std::size_t i, const Complex* v);

  // Line i written as to[j] = from[j] (scale chirp[j]) by chirp_product_power (`chirp`: n real parts, then
  // n imaginary parts), its sums taken in the same loop.
  void add_product(std::size_t i, const Complex* from, Complex scale,
                   const std::vector<double>& chirp, Complex* to);

  Extent result() const;

 private:
  std::size_t n_, border_;
  std::vector<double> total_, edge_;
  std::vector<std::vector<double>> radial_;
  std::vector<double> w2_;  // (j - n/2)^2 for even j, at j / 2

  void set_totals(std::size_t i, LinePower p);
  void add_radial(std::size_t i, const double* squares);
};

}  // namespace lidar_overlap::detail
