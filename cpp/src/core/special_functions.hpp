// Special functions the overlap integrals share.
#pragma once

#include <cmath>
#include <cstddef>

#include "core/constants.hpp"

namespace lidar_overlap {

namespace detail {

// Chebyshev series c0 / 2 + sum_k c_k T_k(t), t in [-1, 1] (Clenshaw's recurrence).
template <std::size_t N>
inline double chebyshev(const double (&c)[N], double t) {
  double b1 = 0.0, b2 = 0.0;
  for (std::size_t k = N - 1; k >= 1; --k) {
    const double b0 = c[k] + 2.0 * t * b1 - b2;
    b2 = b1;
    b1 = b0;
  }
  return 0.5 * c[0] + t * b1 - b2;
}

// exp(-x) I0(x) on [0, 8] in t = x / 4 - 1, and sqrt(x) exp(-x) I0(x) on [8, inf) in t = 16 / x - 1: the
// interpolants at 40 Chebyshev nodes of the power series of I0 summed to 50 digits (scripts/bessel_i0e_series.py),
// truncated where the coefficients fall below 1e-18 (relative error ~1e-16).
inline constexpr double kI0eNear[] = {
    6.76795274409476066e-01,  -3.04682672343198402e-01, 1.71620901522208769e-01,
    -9.49010970480476390e-02, 4.93052842396707117e-02,  -2.37374148058994705e-02,
    1.05464603945949979e-02,  -4.32430999505057593e-03, 1.63947561694133574e-03,
    -5.76375574538582356e-04, 1.88502885095841649e-04,  -5.75419501008210397e-05,
    1.64484480707288956e-05,  -4.41673835845875052e-06, 1.11738753912010366e-06,
    -2.67079385394061193e-07, 6.04699502254191863e-08,  -1.30002500998624805e-08,
    2.65982372468238660e-09,  -5.18979560163526271e-10, 9.67580903537323697e-11,
    -1.72682629144155587e-11, 2.95505266312963988e-12,  -4.85644678311192896e-13,
    7.67618549860493607e-14,  -1.16853328779934514e-14, 1.71539128555513307e-15,
    -2.43127984654795490e-16, 3.33079451882223839e-17,  -4.41534164647933951e-18};
inline constexpr double kI0eFar[] = {
    8.04490411014108786e-01,  3.36911647825569429e-03,  6.88975834691682454e-05,
    2.89137052083475665e-06,  2.04891858946906384e-07,  2.26666899049817804e-08,
    3.39623202570838651e-09,  4.94060238822497006e-10,  1.18891471078464390e-11,
    -3.14991652796324165e-11, -1.32158118404477133e-11, -1.79417853150680615e-12,
    7.18012445138366601e-13,  3.85277838274214259e-13,  1.54008621752140996e-14,
    -4.15056934728722224e-14, -9.55484669882830731e-15, 3.81168066935262083e-15,
    1.77256013305652454e-15,  -3.42548561967714208e-16, -2.82762398051664577e-16,
    3.46122286769565793e-17,  4.46562142030207778e-17,  -4.83050448596401048e-18,
    -7.23318048804384428e-18, 9.92147541565703770e-19,  1.19365089094186928e-18};

// exp(-x) I1(x) / x on [0, 8] (I1 ~ x / 2 near 0: relative error kept there) and sqrt(x) exp(-x) I1(x) beyond, as
// above: I1 is the derivative of the Marcum Q function in its first argument.
inline constexpr double kI1eNear[] = {
    2.52587186443633649e-01,  -1.76416518357834062e-01, 1.02643658689847095e-01,
    -5.29459812080949888e-02, 2.47264490306265163e-02,  -1.05640848946261974e-02,
    4.15642294431288820e-03,  -1.51357245063125315e-03, 5.12285956168575759e-04,
    -1.61760815825896743e-04, 4.78156510755005422e-05,  -1.32731636560394359e-05,
    3.47025130813767845e-06,  -8.56872026469545475e-07, 2.00329475355213533e-07,
    -4.44505912879632805e-08, 9.38153738649577259e-09,  -1.88724975172282944e-09,
    3.62559028155211725e-10,  -6.66348972350202712e-11, 1.17361862988909012e-11,
    -1.98397439776494364e-12, 3.22379336594557476e-13,  -5.04218550472791179e-14,
    7.60068429473540767e-15,  -1.10559694773538625e-15, 1.55363195773620054e-16,
    -2.11142121435816596e-17, 2.77791411276104637e-18};
inline constexpr double kI1eFar[] = {
    7.78576235018280105e-01,  -9.76109749136146870e-03, -1.10588938762623713e-04,
    -3.88256480887769059e-06, -2.51223623787020884e-07, -2.63146884688951959e-08,
    -3.83538038596423700e-09, -5.58974346219658378e-10, -1.89749581235054126e-11,
    3.25260358301548844e-11,  1.41258074366137819e-11,  2.03562854414708956e-12,
    -7.19855177624590836e-13, -4.08355111109219740e-13, -2.10154184277266430e-14,
    4.27244001671195168e-14,  1.04202769841288021e-14,  -3.81440307243700675e-15,
    -1.88035477551078054e-15, 3.30820231092085013e-16,  2.96262899764601565e-16,
    -3.20952592199163711e-17, -4.65030536849478266e-17, 4.41434832309393674e-18,
    7.51729631101139754e-18,  -9.31417887090726310e-19, -1.24219327527599284e-18};

}  // namespace detail

// exp(-x) I0(x) for x >= 0, without overflow. Chebyshev series: the Rice density evaluates it at every
// scatterer, and std::cyl_bessel_i costs ~0.5 us a call, most of an off-axis beam's ray tracing.
inline double scaled_bessel_i0(double x) {
  if (x <= 8.0) return detail::chebyshev(detail::kI0eNear, 0.25 * x - 1.0);
  return detail::chebyshev(detail::kI0eFar, 16.0 / x - 1.0) / std::sqrt(x);
}

// exp(-x) I1(x) for x >= 0, without overflow (Chebyshev series as scaled_bessel_i0).
inline double scaled_bessel_i1(double x) {
  if (x <= 8.0) return x * detail::chebyshev(detail::kI1eNear, 0.25 * x - 1.0);
  return detail::chebyshev(detail::kI1eFar, 16.0 / x - 1.0) / std::sqrt(x);
}

// J0(x) and J1(x): the C library's (POSIX j0, j1), ~0.1 us a call and within ~1e-15 of the value, where
// std::cyl_bessel_j costs ~7 us at the arguments of the Fourier-optics integrals (x up to ~1e3) and strays
// by up to 3e-14 there.
inline double bessel_j0(double x) { return ::j0(x); }
inline double bessel_j1(double x) { return ::j1(x); }

}  // namespace lidar_overlap
