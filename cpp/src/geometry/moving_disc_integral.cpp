#include "geometry/moving_disc_integral.hpp"

#include <algorithm>
#include <cmath>

#include "core/constants.hpp"
#include "core/quadrature.hpp"
#include "core/special_functions.hpp"

namespace lidar_overlap::beam_integral {

namespace {

// Radii q about mu where Lambda(q) has a kink: circle(mu, q) tangent to a fixed disc or to a sector's arc,
// through a corner of a sector (or of a centred fixed disc's circle with a sector's edge), or tangent to a
// sector's straight edge (a weaker kink, the area stays C1).
std::vector<double> kink_radii(const Disc* fixed, std::size_t n_fixed, const std::vector<AnnularSector>& sectors,
                               Vec2 mu) {
  std::vector<double> q;
  const double m = norm(mu);
  for (std::size_t i = 0; i < n_fixed; ++i) {
    const double d = norm(mu - fixed[i].center);
    q.push_back(d + fixed[i].radius);
    q.push_back(std::abs(d - fixed[i].radius));
  }
  for (const AnnularSector& s : sectors) {
    for (double arc : {s.inner, s.outer}) {
      q.push_back(m + arc);
      q.push_back(std::abs(m - arc));
    }
    if (s.span >= 2.0 * kPi) continue;
    for (double angle : {s.start, s.start + s.span}) {
      const Vec2 u{std::cos(angle), std::sin(angle)};
      for (double radius : {s.inner, s.outer}) q.push_back(norm(mu - radius * u));
      for (std::size_t i = 0; i < n_fixed; ++i)
        if (fixed[i].center.x == 0.0 && fixed[i].center.y == 0.0) q.push_back(norm(mu - fixed[i].radius * u));
      const double along = dot(mu, u);
      if (along > s.inner && along < s.outer) q.push_back(std::abs(u.x * mu.y - u.y * mu.x));
    }
  }
  return q;
}

}  // namespace

std::optional<RangeResult> moving_disc_integral(const CouplingTerm& term, const std::vector<AnnularSector>& sectors,
                                                Vec2 center, double w, double tolerance, std::size_t max_segments) {
  if (term.n_gates != 0) return std::nullopt;
  Disc discs[kMaxDiscs];
  std::size_t n_fixed = 0;
  const MovingDisc* moving = nullptr;
  for (std::size_t i = 0; i < term.n_discs; ++i) {
    const MovingDisc& d = term.discs[i];
    if (d.scale != 0.0) {
      if (moving) return std::nullopt;
      moving = &d;
    } else {
      if (n_fixed + 1 >= kMaxDiscs) return std::nullopt;
      discs[n_fixed++] = {d.shift, d.radius};
    }
  }
  if (!moving) return std::nullopt;

  const Vec2 mu = moving->scale * center + moving->shift;
  const double sigma = 0.5 * std::abs(moving->scale) * w, var = sigma * sigma, r = moving->radius;
  // The kernel is below exp(-50) of its peak beyond 10 sigma from r (a Gaussian in q about r when r >> sigma,
  // q exp(-q^2 / 2 sigma^2) when r << sigma).
  const double lo = std::max(0.0, r - 10.0 * sigma), hi = r + 10.0 * sigma;
  std::vector<double> points{lo, hi};
  for (double q : kink_radii(discs, n_fixed, sectors, mu))
    if (q > lo && q < hi) points.push_back(q);
  std::sort(points.begin(), points.end());

  // Fixed discs centred on the aperture's centre (the aperture, a shadow in its plane) only cut the sectors'
  // outer radius: Lambda is then one disc's area per sector, by Green's theorem.
  bool centred = true;
  double cut = HUGE_VAL;
  for (std::size_t i = 0; i < n_fixed; ++i) {
    centred = centred && discs[i].center.x == 0.0 && discs[i].center.y == 0.0;
    cut = std::min(cut, discs[i].radius);
  }
  std::vector<AnnularSector> cut_sectors;
  if (centred)
    for (AnnularSector s : sectors) {
      s.outer = std::min(s.outer, cut);
      if (s.outer > s.inner) cut_sectors.push_back(s);
    }
  auto area_within = [&](double q) {
    double area = 0.0;
    if (centred) {
      for (const AnnularSector& s : cut_sectors) area += disc_sector_area(mu, q, s);
    } else {
      discs[n_fixed] = {mu, q};
      for (const AnnularSector& s : sectors) area += sector_intersection_area(discs, n_fixed + 1, s);
    }
    return area;
  };
  auto integrand = [&](double q) {
    const double d = q - r, g = std::exp(-0.5 * d * d / var);
    if (g == 0.0) return 0.0;
    return term.weight * area_within(q) * (r / var * g * scaled_bessel_i1(q * r / var));
  };
  const QuadratureResult result = integrate(integrand, points.data(), points.size(), tolerance, max_segments);
  return RangeResult{result.value, result.error, result.evaluations, result.converged};
}

}  // namespace lidar_overlap::beam_integral
