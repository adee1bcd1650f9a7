// The beam integral of the RT engine: a coupling term weighted by the Gaussian beam irradiance at one
// range, by adaptive quadrature with breakpoints where the term has a kink (docs/rt_method.md). Shared by
// the full-aperture overlap (overlap_rt.cpp) and the masked one (pupil/aperture_mask.cpp): a term is anything
// callable on a scatterer position whose kinks lie on known circles in the scatterer plane.
// Internal header, not installed.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "core/constants.hpp"
#include "core/quadrature.hpp"
#include "core/special_functions.hpp"
#include "geometry/circles.hpp"
#include "geometry/coupling_term.hpp"

namespace lidar_overlap::beam_integral {

// Room for a term's kink circles: 5 moving discs give 20 tangency circles; a masked term adds its discs'
// tangencies with the sectors' arcs and passages through their corners (pupil/aperture_mask.cpp).
inline constexpr std::size_t kMaxKinks = 64;

struct RangeResult {
  double value = 0.0, error = 0.0;
  std::size_t evaluations = 0;
  bool converged = true;
  void add(const RangeResult& o) {
    value += o.value;
    error += o.error;
    evaluations += o.evaluations;
    converged = converged && o.converged;
  }
};

// Circles in the scatterer plane across which a term has a kink.
struct Kinks {
  Disc circles[kMaxKinks];
  std::size_t n = 0;
  Kinks() = default;
  explicit Kinks(const CouplingTerm& t) : n(t.kink_circles(circles, kMaxKinks)) {}
};

// Distances t > 0 at which the ray center + t dir (|dir| = 1) crosses a kink circle.
inline std::size_t crossings(const Kinks& k, Vec2 center, Vec2 dir, double* out) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < k.n; ++i) {
    const Vec2 q = center - k.circles[i].center;
    const double half_b = dot(q, dir), c = dot(q, q) - k.circles[i].radius * k.circles[i].radius;
    const double disc = half_b * half_b - c;
    if (disc < 0.0) continue;
    const double h = -(half_b + std::copysign(std::sqrt(disc), half_b));  // stable roots h and c/h
    for (double t : {h, h != 0.0 ? c / h : 0.0})
      if (t > 0.0 && std::isfinite(t)) out[n++] = t;
  }
  return n;
}

// Sorted breakpoints: lo, the crossings inside (lo, hi), hi.
inline std::size_t breakpoints(const Kinks& k, Vec2 center, Vec2 dir, double lo, double hi,
                               double* points) {
  double radii[2 * kMaxKinks];
  const std::size_t nk = crossings(k, center, dir, radii);
  std::size_t n = 0;
  points[n++] = lo;
  for (std::size_t i = 0; i < nk; ++i) {
    if (radii[i] > lo && radii[i] < hi) points[n++] = radii[i];
  }
  points[n++] = hi;
  std::sort(points, points + n);
  return n;
}

// int term(origin + rho dir) p(rho) d rho, with p the density of the distance from `origin` of a
// point of the Gaussian beam (1/e^2 radius w, so sigma = w/2) centred `nu` away: the Rice density,
// Rayleigh for nu = 0. For a term symmetric about `origin` this is its beam-weighted mean whatever
// the beam offset; with nu = 0 and the origin at the beam centre it is the mean along `dir`.
template <class Term>
RangeResult radial_integral(const Term& term, const Kinks& kinks, Vec2 origin, double nu, double w,
                            Vec2 dir, double tolerance, std::size_t max_segments) {
  const double var = 0.25 * w * w;
  // Beyond 10 sigma = 5 w from nu the density is below exp(-50) of its peak.
  const double lo = std::max(0.0, nu - 5.0 * w), hi = nu + 5.0 * w;
  double points[2 * kMaxKinks + 2];
  const std::size_t n = breakpoints(kinks, origin, dir, lo, hi, points);
  auto integrand = [&](double rho) {
    const double d = rho - nu;
    const double density =
        rho / var * std::exp(-0.5 * d * d / var) * scaled_bessel_i0(rho * nu / var);
    return density == 0.0 ? 0.0 : density * term(origin + rho * dir);
  };
  const QuadratureResult q = integrate(integrand, points, n, tolerance, max_segments);
  return {q.value, q.error, q.evaluations, q.converged};
}

// True when every disc and gate of `term` shifts along the line through the origin and `center`: the term
// is then mirror-symmetric about that line.
inline bool mirror_symmetric(const CouplingTerm& term, Vec2 center) {
  bool mirror = true;
  for (std::size_t i = 0; i < term.n_discs; ++i) {
    const Vec2 b = term.discs[i].shift;
    mirror = mirror && (b.x * center.y - b.y * center.x) == 0.0;
  }
  for (std::size_t g = 0; g < term.n_gates; ++g) {
    const Vec2 b = term.gates[g].shift;
    mirror = mirror && (b.x * center.y - b.y * center.x) == 0.0;
  }
  return mirror;
}

// A term with no centre of symmetry: the mean over directions of the radial mean from the beam centre;
// with `mirror` (the term is mirror-symmetric about the line through the origin and the centre) half the
// directions suffice.
template <class Term>
RangeResult planar_mean(const Term& term, const Kinks& kinks, Vec2 center, double w, bool mirror,
                        double tolerance, std::size_t max_segments) {
  const double phi0 = (center.x != 0.0 || center.y != 0.0) ? std::atan2(center.y, center.x) : 0.0;
  const double span = mirror ? kPi : 2.0 * kPi;

  // The radial mean is not smooth in direction where a ray from the beam centre grazes a kink
  // circle: those tangent directions become breakpoints of the angular integral.
  double breaks[2 * kMaxKinks + 3];
  std::size_t nb = 0;
  for (double f : {0.0, 0.5, 1.0}) breaks[nb++] = f * span;
  for (std::size_t i = 0; i < kinks.n; ++i) {
    const Vec2 q = kinks.circles[i].center - center;
    const double d = norm(q), rho = kinks.circles[i].radius;
    if (!(d > rho)) continue;
    const double mid = std::atan2(q.y, q.x) - phi0, half = std::asin(rho / d);
    for (double phi : {mid - half, mid + half}) {
      phi = std::remainder(phi, 2.0 * kPi);  // (-pi, pi]
      if (mirror)
        phi = std::abs(phi);  // the lower half mirrors the upper one
      else if (phi < 0.0)
        phi += 2.0 * kPi;
      if (phi > 0.0 && phi < span) breaks[nb++] = phi;
    }
  }
  std::sort(breaks, breaks + nb);

  RangeResult inner;
  double inner_error = 0.0;
  auto mean_over_direction = [&](double phi) {
    const double a = phi0 + phi;
    const RangeResult r = radial_integral(term, kinks, center, 0.0, w, {std::cos(a), std::sin(a)},
                                          0.25 * tolerance, max_segments);
    inner.evaluations += r.evaluations;
    inner.converged = inner.converged && r.converged;
    inner_error = std::max(inner_error, r.error);
    return r.value / span;
  };
  const QuadratureResult q =
      integrate(mean_over_direction, breaks, nb, 0.75 * tolerance, max_segments);
  return {q.value, q.error + inner_error, inner.evaluations, inner.converged && q.converged};
}

}  // namespace lidar_overlap::beam_integral
