#include "lidar_overlap/pupil/zernike.hpp"

#include <cmath>
#include <cstdlib>

#include "core/checks.hpp"

namespace lidar_overlap {

ZernikeIndex noll_index(int j, const char* parameter) {
  if (j < 1 || j > 1000) checks::fail(parameter, j, "a Noll index in [1, 1000]");
  int n = 0;
  while ((n + 1) * (n + 2) / 2 < j) ++n;
  // Within order n, |m| runs up from n mod 2 in pairs; even j takes cos (m > 0), odd j sin (m < 0).
  const int k = j - n * (n + 1) / 2 - 1;  // 0 ... n
  const int abs_m = (n % 2 == 0) ? 2 * ((k + 1) / 2) : 2 * (k / 2) + 1;
  const int m = (abs_m == 0) ? 0 : (j % 2 == 0 ? abs_m : -abs_m);
  return {n, m};
}

namespace {

// R_n^|m|(rho), dR/drho and R/rho (finite at 0 for |m| >= 1), by the explicit sum.
struct Radial {
  double value = 0.0, derivative = 0.0, over_rho = 0.0;
};

Radial radial(int n, int abs_m, double rho) {
  Radial r;
  double coefficient = 1.0;  // (-1)^k (n-k)! / (k! ((n+m)/2-k)! ((n-m)/2-k)!), built term by term
  for (int i = 2; i <= n; ++i) coefficient *= i;
  for (int i = 2; i <= (n + abs_m) / 2; ++i) coefficient /= i;
  for (int i = 2; i <= (n - abs_m) / 2; ++i) coefficient /= i;
  for (int k = 0; k <= (n - abs_m) / 2; ++k) {
    const int power = n - 2 * k;
    r.value += coefficient * std::pow(rho, power);
    if (power >= 1) {
      r.derivative += coefficient * power * std::pow(rho, power - 1);
      r.over_rho += coefficient * std::pow(rho, power - 1);
    }
    if (2 * (k + 1) > n - abs_m)
      break;  // the last term (its update would divide by n - k = 0 for n = 0)
    // Next coefficient: k -> k+1.
    const double a = (n + abs_m) / 2 - k, b = (n - abs_m) / 2 - k;
    coefficient *= -(a * b) / ((k + 1.0) * (n - k));
  }
  return r;
}

double normalisation(ZernikeIndex z) { return std::sqrt((z.m == 0 ? 1.0 : 2.0) * (z.n + 1)); }

}  // namespace

double zernike(int j, Vec2 p) {
  const ZernikeIndex z = noll_index(j);
  const int abs_m = std::abs(z.m);
  const double rho = norm(p), theta = std::atan2(p.y, p.x);
  const double angular = z.m > 0   ? std::cos(abs_m * theta)
                         : z.m < 0 ? std::sin(abs_m * theta)
                                   : 1.0;
  return normalisation(z) * radial(z.n, abs_m, rho).value * angular;
}

Vec2 zernike_gradient(int j, Vec2 p) {
  const ZernikeIndex z = noll_index(j);
  const int abs_m = std::abs(z.m);
  const double rho = norm(p), theta = std::atan2(p.y, p.x);
  const double c = std::cos(theta), s = std::sin(theta);
  const Radial r = radial(z.n, abs_m, rho);
  // d/dx = cos(theta) d/drho - sin(theta)/rho d/dtheta, d/dy = sin(theta) d/drho + cos(theta)/rho d/dtheta.
  double angular = 1.0, angular_derivative = 0.0;
  if (z.m > 0) {
    angular = std::cos(abs_m * theta);
    angular_derivative = -abs_m * std::sin(abs_m * theta);
  } else if (z.m < 0) {
    angular = std::sin(abs_m * theta);
    angular_derivative = abs_m * std::cos(abs_m * theta);
  }
  const double radial_part = r.derivative * angular, tangential = r.over_rho * angular_derivative;
  const double scale = normalisation(z);
  return {scale * (c * radial_part - s * tangential), scale * (s * radial_part + c * tangential)};
}

}  // namespace lidar_overlap
