#include "fourier/extent_sums.hpp"

#include <algorithm>
#include <cmath>

#include "core/team.hpp"

namespace lidar_overlap::detail {

namespace {
// The calling thread's buffers for one line: its values' |v_j|^2, and the radial bins of its even samples.
double* line_squares(std::size_t n) {
  thread_local std::vector<double> squares;
  if (squares.size() < n) squares.resize(n);
  return squares.data();
}
int* line_bins(std::size_t count) {
  thread_local std::vector<int> bins;
  if (bins.size() < count) bins.resize(count);
  return bins.data();
}
}  // namespace

double Extent::radius(double fraction, double dx) const {
  double sampled = 0.0, inside = 0.0;
  for (double p : radial) sampled += p;
  for (std::size_t b = 0; b < radial.size(); ++b) {
    inside += radial[b];
    if (inside >= fraction * sampled) return dx * std::sqrt((b + 1) * n / 8.0);
  }
  return dx * std::sqrt(radial.size() * n / 8.0);
}

ExtentSums::ExtentSums(std::size_t n, int threads, bool radial)
    : n_(n),
      border_(std::max<std::size_t>(1, n / 16)),
      total_(n),
      edge_(n),
      radial_(radial ? threads : 0, std::vector<double>(4 * n + 2, 0.0)) {
  if (!radial) return;
  w2_.resize(n / 2 + 1);
  for (std::size_t j = 0; j < n; j += 2) {
    const double w = static_cast<double>(j) - 0.5 * static_cast<double>(n);
    w2_[j / 2] = w * w;
  }
}

void ExtentSums::add(std::size_t i, const Complex* v) {
  const bool end = i < border_ || i >= n_ - border_;
  const double total = power(v, n_);
  set_totals(i, {total, end ? total : power(v, border_) + power(v + n_ - border_, border_)});
  if (radial_.empty() || i % 2) return;
  // |v|^2 written out: libstdc++'s std::norm squares std::abs (a hypot) unless compiled for fast math.
  double* squares = line_squares(n_);
  for (std::size_t j = 0; j < n_; j += 2)
    squares[j] = v[j].real() * v[j].real() + v[j].imag() * v[j].imag();
  add_radial(i, squares);
}

void ExtentSums::add_product(std::size_t i, const Complex* from, Complex scale,
                             const std::vector<double>& chirp, Complex* to) {
  double* squares = radial_.empty() || i % 2 ? nullptr : line_squares(n_);
  set_totals(i, chirp_product_power(from, scale, chirp.data(), chirp.data() + n_, to, n_, border_,
                                    squares));
  if (squares) add_radial(i, squares);
}

Extent ExtentSums::result() const {
  Extent e(n_);
  for (std::size_t i = 0; i < n_; ++i) {
    e.total += total_[i];
    e.border += edge_[i];
  }
  for (const std::vector<double>& bins : radial_)
    for (std::size_t b = 0; b < bins.size(); ++b) e.radial[b] += bins[b];
  return e;
}

void ExtentSums::set_totals(std::size_t i, LinePower p) {
  total_[i] = p.total;
  edge_[i] = i < border_ || i >= n_ - border_ ? p.total : p.ends;
}

// Every other line and sample (weighted 4) resolve the profile to two samples at a quarter of the cost.
void ExtentSums::add_radial(std::size_t i, const double* squares) {
  std::vector<double>& bins = radial_[static_cast<std::size_t>(team_member())];
  const double u = static_cast<double>(i) - 0.5 * static_cast<double>(n_), u2 = u * u,
               per_bin = 8.0 / static_cast<double>(n_), last = static_cast<double>(bins.size() - 1);
  // Sample k (at w = 2k - n/2) and sample half - k (at -w) fall in the same bin: the bins of k <= half/2
  // only, two per instruction (min(last, floor) taken before the conversion: the same bin for these sums
  // >= 0, and a conversion to 32 bits that vectorises), then each mirrored pair summed into its bin once.
  // A bin's sum then differs in its last bits from a sample-by-sample sum (as it does between thread
  // counts): an extent moves only where a cumulative sum meets its threshold exactly.
  const std::size_t half = n_ / 2, mid = half / 2;
  int* slot = line_bins(mid + 1);
  for (std::size_t k = 0; k <= mid; ++k)
    slot[k] = static_cast<int>(std::min(last, (w2_[k] + u2) * per_bin));
  // w = -n/2: its mirror is not sampled.
  bins[static_cast<std::size_t>(slot[0])] += 4.0 * squares[0];
  for (std::size_t k = 1; k < half - k; ++k)
    bins[static_cast<std::size_t>(slot[k])] += 4.0 * (squares[2 * k] + squares[2 * (half - k)]);
  if (half % 2 == 0) bins[static_cast<std::size_t>(slot[mid])] += 4.0 * squares[half];  // w = 0
}

}  // namespace lidar_overlap::detail
