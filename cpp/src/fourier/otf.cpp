#include "fourier/otf.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "core/constants.hpp"
#include "core/special_functions.hpp"

namespace lidar_overlap {

namespace {

// J_0(x) ... J_N(x) by Miller's backward recurrence, normalised by J_0 + 2 sum J_2k = 1; orders where
// J_n < 1e-18 are dropped. Exact to rounding for every x >= 0 and costs O(x) multiply-adds.
void bessel_sequence(double x, std::vector<double>& j) {
  if (x < 1e-8) {  // J_2 and beyond below 1e-17; also keeps 2n/x, the growth per step, finite
    j.assign({1.0 - 0.25 * x * x, 0.5 * x});
    return;
  }
  // Beyond n = x + 12 x^(1/3) + 25 the orders fall below 1e-17; start well above for full accuracy.
  const std::size_t n_keep = static_cast<std::size_t>(x + 12.0 * std::cbrt(x) + 25.0);
  std::size_t m = n_keep + 20 + static_cast<std::size_t>(std::sqrt(40.0 * n_keep));
  m += m % 2;
  j.resize(m + 2);
  j[m + 1] = 0.0;
  j[m] = 1e-300;
  const double two_over_x = 2.0 / x;
  double norm = 0.0;  // J_0 + 2 sum J_2k, accumulated on the way down
  // Two steps at a time from (J_n, J_n+1), n even: J_n-1 = t_n J_n - J_n+1 and
  // J_n-2 = (t_n-1 t_n - 1) J_n - t_n-1 J_n+1 (t_n = 2n/x) shorten the dependency chain to one step.
  for (std::size_t n = m; n >= 2; n -= 2) {
    const double t_n = n * two_over_x, t_m = (n - 1) * two_over_x;
    const double a = j[n], b = j[n + 1];
    norm += 2.0 * a;
    j[n - 1] = t_n * a - b;
    j[n - 2] = (t_m * t_n - 1.0) * a - t_m * b;
    if (std::abs(j[n - 2]) >
        1e250) {  // rescale to stay in range (large orders at small x grow fast)
      for (std::size_t k = n - 2; k <= m; ++k) j[k] *= 1e-250;
      norm *= 1e-250;
    }
  }
  norm += j[0];
  j.resize(n_keep + 1);
  const double inverse_norm = 1.0 / norm;
  for (double& v : j) v *= inverse_norm;
}

// int_{phi_lo}^{phi_hi} 2 r^2 sin^2(phi) cos(beta c + x cos phi) d phi with x = beta r: the part of
// int L(x') cos(beta x') dx' where the chord length L is that of the circle (centre c on the axis,
// radius r), x' = c + r cos(phi). Jacobi-Anger, exp(i x cos phi) = sum eps_n i^n J_n(x) cos(n phi),
// leaves integrals of sin^2(phi) cos(n phi) in closed form: no quadrature, no oscillation to resolve.
double arc_part(double r, double beta_c, const std::vector<double>& j, double phi_lo,
                double phi_hi) {
  if (!(phi_hi > phi_lo)) return 0.0;
  const std::size_t n_max = j.size() - 1;
  // C_m = int cos(m phi) = (sin(m phi_hi) - sin(m phi_lo)) / m, sines by rotation (error ~ m eps).
  thread_local std::vector<double> c, inverse;
  c.resize(n_max + 3);
  for (std::size_t m = inverse.size(); m < c.size(); ++m) inverse.push_back(m ? 1.0 / m : 0.0);
  c[0] = phi_hi - phi_lo;
  const std::complex<double> step_hi = std::polar(1.0, phi_hi), step_lo = std::polar(1.0, phi_lo);
  const std::complex<double> step2_hi = step_hi * step_hi, step2_lo = step_lo * step_lo;
  std::complex<double> e_hi = step_hi, e_lo = step_lo, f_hi = step2_hi,
                       f_lo = step2_lo;  // odd and even m
  // Products written out: the same bits as std::complex's, without its branch for NaN results.
  auto times = [](std::complex<double> a, std::complex<double> b) {
    return std::complex<double>(a.real() * b.real() - a.imag() * b.imag(),
                                a.real() * b.imag() + a.imag() * b.real());
  };
  for (std::size_t m = 1; m + 1 < c.size(); m += 2) {
    c[m] = (e_hi.imag() - e_lo.imag()) * inverse[m];
    c[m + 1] = (f_hi.imag() - f_lo.imag()) * inverse[m + 1];
    e_hi = times(e_hi, step2_hi);
    e_lo = times(e_lo, step2_lo);
    f_hi = times(f_hi, step2_hi);
    f_lo = times(f_lo, step2_lo);
  }
  if (c.size() % 2 == 0) c.back() = (e_hi.imag() - e_lo.imag()) * inverse[c.size() - 1];
  // S_n = int sin^2(phi) cos(n phi) = C_n / 2 - (C_{n+2} + C_{|n-2|}) / 4, weighted by eps_n i^n J_n.
  auto s_n = [&](std::size_t n) {
    return 0.5 * c[n] - 0.25 * (c[n + 2] + c[n >= 2 ? n - 2 : 2 - n]);
  };
  double sum[4] = {0.0, 0.0, 0.0, 0.0};  // by n mod 4, for i^n = 1, i, -1, -i
  std::size_t n = 1;
  for (; n + 3 <= n_max; n += 4) {
    sum[1] += j[n] * s_n(n);
    sum[2] += j[n + 1] * s_n(n + 1);
    sum[3] += j[n + 2] * s_n(n + 2);
    sum[0] += j[n + 3] * s_n(n + 3);
  }
  for (; n <= n_max; ++n) sum[n % 4] += j[n] * s_n(n);
  const double re = j[0] * s_n(0) + 2.0 * (sum[0] - sum[2]), im = 2.0 * (sum[1] - sum[3]);
  return 2.0 * r * r * (std::cos(beta_c) * re - std::sin(beta_c) * im);
}

// int over the intersection of disc(r1, centre -v/2) and disc(r2, centre +v/2) of cos(beta x) dA,
// with j1, j2 the Bessel sequences at beta r1 and beta r2.
double lens_cosine_integral(double r1, double r2, double v, double beta,
                            const std::vector<double>& j1, const std::vector<double>& j2) {
  const double c1 = -0.5 * v, c2 = 0.5 * v;
  if (v >= r1 + r2) return 0.0;
  const double lo = std::max(c1 - r1, c2 - r2), hi = std::min(c1 + r1, c2 + r2);
  if (!(hi > lo)) return 0.0;
  // The chord is bounded by circle 2 left of x_k and by circle 1 right of it.
  const double xk =
      v > 0.0 ? std::clamp((r1 * r1 - r2 * r2) / (2.0 * v), lo, hi) : (r1 <= r2 ? lo : hi);
  auto angle = [](double x, double c, double r) {
    return std::acos(std::clamp((x - c) / r, -1.0, 1.0));
  };
  // Two equal discs: the two arcs, each ending on the axis of symmetry x = 0, are mirror images and
  // cos(beta x) is even.
  if (r1 == r2) return 2.0 * arc_part(r1, beta * c1, j1, angle(hi, c1, r1), angle(0.0, c1, r1));
  return arc_part(r2, beta * c2, j2, angle(xk, c2, r2), angle(lo, c2, r2)) +
         arc_part(r1, beta * c1, j1, angle(hi, c1, r1), angle(xk, c1, r1));
}

}  // namespace

double annular_otf(const AnnularPupil& p, double v) {
  // P(a) P*(a - v) = M(a) M(a - v) exp(i psi (2 a.v - v^2)); about the midpoint of the two centres the
  // phase is 2 psi v x, and the sine part cancels between mirror-image terms, leaving cosines.
  const double beta = 2.0 * p.psi * v;
  if (v >= 2.0 * p.outer) return 0.0;
  thread_local std::vector<double> j_outer, j_inner;
  const double b = std::abs(beta);  // the integrals of cos(beta x) are even in beta
  bessel_sequence(b * p.outer, j_outer);
  double otf = lens_cosine_integral(p.outer, p.outer, v, b, j_outer, j_outer);
  if (p.inner > 0.0) {
    bessel_sequence(b * p.inner, j_inner);
    otf -= lens_cosine_integral(p.outer, p.inner, v, b, j_outer, j_inner) +
           lens_cosine_integral(p.inner, p.outer, v, b, j_inner, j_outer);
    otf += lens_cosine_integral(p.inner, p.inner, v, b, j_inner, j_inner);
  }
  return otf;
}

double disc_transform(double r, double q) {
  if (q == 0.0) return kPi * r * r;
  return r * bessel_j1(2.0 * kPi * q * r) / q;
}

}  // namespace lidar_overlap
