#include "lidar_overlap/otf.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>
#include <vector>

#include "lidar_overlap/constants.hpp"

namespace lidar_overlap {

namespace {

// Gauss-Legendre rule on [-1, 1] with n nodes (Newton on P_n), made once per size and kept.
struct Rule {
  std::vector<double> x, w;
};

const Rule& gauss_legendre(std::size_t n) {
  // Sizes 8 * 2^k only: each rule costs O(m^2) to make, so few sizes are kept.
  static std::array<Rule, 12> rules;
  static std::array<std::once_flag, 12> made;
  std::size_t k = 0;
  while ((std::size_t{8} << k) < n && k + 1 < rules.size()) ++k;
  std::call_once(made[k], [k] {
    const std::size_t m = std::size_t{8} << k;
    Rule& r = rules[k];
    r.x.resize(m);
    r.w.resize(m);
    for (std::size_t i = 0; i < (m + 1) / 2; ++i) {
      double x = std::cos(kPi * (i + 0.75) / (m + 0.5)), dp = 1.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = x;
        for (std::size_t j = 2; j <= m; ++j) {
          const double p2 = ((2.0 * j - 1.0) * x * p1 - (j - 1.0) * p0) / j;
          p0 = p1;
          p1 = p2;
        }
        dp = m * (x * p1 - p0) / (x * x - 1.0);
        const double dx = p1 / dp;
        x -= dx;
        if (std::abs(dx) < 1e-16) break;
      }
      r.x[i] = -x;
      r.x[m - 1 - i] = x;
      r.w[i] = r.w[m - 1 - i] = 2.0 / ((1.0 - x * x) * dp * dp);
    }
  });
  return rules[k];
}

// int_{phi_lo}^{phi_hi} 2 r^2 sin^2(phi) cos(beta (c + r cos phi)) d phi: the part of
// int L(x) cos(beta x) dx where the chord length L is that of the circle (centre c on the x axis, radius r),
// x = c + r cos(phi). Smooth in phi, so Gauss-Legendre converges fast once it resolves the oscillation.
double arc_part(double r, double c, double beta, double phi_lo, double phi_hi) {
  if (!(phi_hi > phi_lo)) return 0.0;
  // The phase beta r cos(phi) sweeps at most beta r (phi_hi - phi_lo) radians; half a node per radian
  // plus a margin (then rounded up to the next rule size) leaves G unchanged to 1e-10 against two.
  const double sweep = std::abs(beta) * r * (phi_hi - phi_lo);
  const Rule& rule = gauss_legendre(static_cast<std::size_t>(24.0 + 0.5 * sweep));
  const double mid = 0.5 * (phi_hi + phi_lo), half = 0.5 * (phi_hi - phi_lo);
  double sum = 0.0;
  for (std::size_t i = 0; i < rule.x.size(); ++i) {
    const double phi = mid + half * rule.x[i];
    const double s = std::sin(phi);
    sum += rule.w[i] * s * s * std::cos(beta * (c + r * std::cos(phi)));
  }
  return 2.0 * r * r * half * sum;
}

// int over the intersection of disc(r1, centre -v/2) and disc(r2, centre +v/2) of cos(beta x) dA.
double lens_cosine_integral(double r1, double r2, double v, double beta) {
  const double c1 = -0.5 * v, c2 = 0.5 * v;
  if (v >= r1 + r2) return 0.0;
  const double lo = std::max(c1 - r1, c2 - r2), hi = std::min(c1 + r1, c2 + r2);
  if (!(hi > lo)) return 0.0;
  // The chord is bounded by circle 2 left of x_k and by circle 1 right of it.
  const double xk = v > 0.0 ? std::clamp((r1 * r1 - r2 * r2) / (2.0 * v), lo, hi) : (r1 <= r2 ? lo : hi);
  auto angle = [](double x, double c, double r) { return std::acos(std::clamp((x - c) / r, -1.0, 1.0)); };
  return arc_part(r2, c2, beta, angle(xk, c2, r2), angle(lo, c2, r2)) +
         arc_part(r1, c1, beta, angle(hi, c1, r1), angle(xk, c1, r1));
}

}  // namespace

double annular_otf(const AnnularPupil& p, double v) {
  // P(a) P*(a - v) = M(a) M(a - v) exp(i psi (2 a.v - v^2)); about the midpoint of the two centres the
  // phase is 2 psi v x, and the sine part cancels between mirror-image terms, leaving cosines.
  const double beta = 2.0 * p.psi * v;
  double otf = lens_cosine_integral(p.outer, p.outer, v, beta);
  if (p.inner > 0.0) {
    otf -= lens_cosine_integral(p.outer, p.inner, v, beta) + lens_cosine_integral(p.inner, p.outer, v, beta);
    otf += lens_cosine_integral(p.inner, p.inner, v, beta);
  }
  return otf;
}

double disc_transform(double r, double q) {
  if (q == 0.0) return kPi * r * r;
  return r * std::cyl_bessel_j(1.0, 2.0 * kPi * q * r) / q;
}

}  // namespace lidar_overlap
