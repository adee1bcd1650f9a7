#include "lidar_overlap/pupil/aberrations.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "lidar_overlap/pupil/zernike.hpp"
#include "pupil/seidel_gradient.hpp"
#include "core/checks.hpp"
#include "core/constants.hpp"

namespace lidar_overlap {

void Aberrations::validate() const {
  if (zernike.size() > kMaxNollIndex)
    checks::fail("aberrations.zernike (highest Noll index)", static_cast<double>(zernike.size()),
                 "at most " + std::to_string(kMaxNollIndex) + " (radial order 20)");
  auto coefficient = [](const std::string& name, double value) {
    if (!(std::abs(value) <= kMaxCoefficient))
      checks::fail(
          name, value,
          "a finite value within +-" + checks::number(kMaxCoefficient) + " m of wavefront");
  };
  for (std::size_t i = 0; i < zernike.size(); ++i)
    coefficient("aberrations.zernike[" + std::to_string(i + 1) + "]", zernike[i]);
  coefficient("aberrations.w040", w040);
  coefficient("aberrations.w131", w131);
  coefficient("aberrations.w222", w222);
  coefficient("aberrations.w220", w220);
  coefficient("aberrations.w311", w311);
  checks::non_negative("aberrations.field_radius", field_radius);
  checks::angle("aberrations.field_radius", field_radius);
  if (field_dependent() && !(field_radius > 0.0))
    checks::fail("aberrations.field_radius", field_radius,
                 "a field angle > 0 rad (the field at H = 1) when W131, W222, W220 or W311 is set");
}

bool Aberrations::field_dependent() const {
  return w131 != 0.0 || w222 != 0.0 || w220 != 0.0 || w311 != 0.0;
}

bool Aberrations::none() const {
  return w040 == 0.0 && !field_dependent() &&
         std::all_of(zernike.begin(), zernike.end(), [](double c) { return c == 0.0; });
}

double Aberrations::wavefront(Vec2 p, Vec2 field) const {
  double w = 0.0;
  for (std::size_t i = 0; i < zernike.size(); ++i)
    if (zernike[i] != 0.0) w += zernike[i] * lidar_overlap::zernike(static_cast<int>(i + 1), p);
  const double r2 = dot(p, p);
  w += w040 * r2 * r2;
  if (field_dependent()) {
    const Vec2 h = (1.0 / field_radius) * field;  // H as a vector: H rho cos = h.p
    const double hp = dot(h, p), h2 = dot(h, h);
    w += w131 * r2 * hp + w222 * hp * hp + w220 * h2 * r2 + w311 * h2 * hp;
  }
  return w;
}

Vec2 Aberrations::gradient(Vec2 p, Vec2 field) const {
  Vec2 g;
  for (std::size_t i = 0; i < zernike.size(); ++i)
    if (zernike[i] != 0.0) g = g + zernike[i] * zernike_gradient(static_cast<int>(i + 1), p);
  const double r2 = dot(p, p);
  g = g + (4.0 * w040 * r2) * p;
  if (field_dependent()) {
    const Vec2 h = (1.0 / field_radius) * field;
    const detail::SeidelFieldGradient s = detail::seidel_field_gradient(*this, p, h);
    g = g + s.along_pupil * p + s.along_field * h;
  }
  return g;
}

double Aberrations::max_gradient(Vec2 field) const {
  double best = 0.0;
  for (int i = 0; i <= 40; ++i)
    for (int k = 0; k < 80; ++k) {
      const double rho = i / 40.0, theta = 2.0 * kPi * k / 80.0;
      best = std::max(best, norm(gradient({rho * std::cos(theta), rho * std::sin(theta)}, field)));
    }
  return best;
}

void PupilPolynomial::row(double y, double* out) const {
  const int stride = degree + 1;
  for (int p = 0; p <= degree; ++p) {
    double v = 0.0;
    for (int q = degree - p; q >= 0; --q) v = v * y + c[p * stride + q];  // Horner in y
    out[p] = v;
  }
}

PupilPolynomial Aberrations::pupil_polynomial() const {
  constexpr int kMaxDegree = 16;
  PupilPolynomial poly;
  poly.degree = w040 != 0.0 ? 4 : 0;
  for (std::size_t i = 0; i < zernike.size(); ++i)
    if (zernike[i] != 0.0)
      poly.degree = std::max(poly.degree, noll_index(static_cast<int>(i + 1)).n);
  if (poly.degree > kMaxDegree) return {-1, {}};
  const int stride = poly.degree + 1;
  poly.c.assign(stride * stride, 0.0);
  auto binomial = [](int n, int k) {
    double b = 1.0;
    for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
    return b;
  };
  // a (x^2 + y^2)^s Re or Im (x + i y)^m, expanded binomially.
  auto add = [&](double a, int s, int m, bool imaginary) {
    for (int u = 0; u <= s; ++u)
      for (int t = imaginary ? 1 : 0; t <= m; t += 2) {
        const double sign = ((imaginary ? t - 1 : t) / 2) % 2 ? -1.0 : 1.0;
        poly.c[(2 * u + m - t) * stride + 2 * (s - u) + t] +=
            a * binomial(s, u) * binomial(m, t) * sign;
      }
  };
  if (w040 != 0.0) add(w040, 2, 0, false);
  for (std::size_t i = 0; i < zernike.size(); ++i) {
    if (zernike[i] == 0.0) continue;
    const ZernikeIndex z = noll_index(static_cast<int>(i + 1));
    const int m = std::abs(z.m);
    const double norm_factor = std::sqrt((m == 0 ? 1.0 : 2.0) * (z.n + 1));
    double coefficient =
        binomial(z.n, (z.n - m) / 2);  // R_n^m's leading coefficient, then its recurrence
    for (int k = 0; k <= (z.n - m) / 2; ++k) {
      add(zernike[i] * norm_factor * coefficient, (z.n - 2 * k - m) / 2, m, z.m < 0);
      const double a = (z.n + m) / 2 - k, b = (z.n - m) / 2 - k;
      coefficient *= -(a * b) / ((k + 1.0) * (z.n - k));
    }
  }
  return poly;
}

}  // namespace lidar_overlap
