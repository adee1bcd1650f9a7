#include "geometry/moving_disc_integral.hpp"

#include <algorithm>
#include <cmath>

#include "core/constants.hpp"
#include "core/quadrature.hpp"
#include "core/special_functions.hpp"
#include "geometry/disc_sector_areas.hpp"

namespace lidar_overlap::beam_integral {

namespace {

// Radii q about mu where Lambda(q) has a kink: circle(mu, q) tangent to a fixed disc or to a sector's arc,
// through a corner of a sector (or of a centred fixed disc's circle with a sector's edge), or tangent to a
// sector's straight edge (a weaker kink, the area stays C1).
std::vector<double> kink_radii(const Disc* fixed, std::size_t n_fixed,
                               const std::vector<AnnularSector>& sectors, Vec2 mu) {
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
        if (fixed[i].center.x == 0.0 && fixed[i].center.y == 0.0)
          q.push_back(norm(mu - fixed[i].radius * u));
      const double along = dot(mu, u);
      if (along > s.inner && along < s.outer) q.push_back(std::abs(u.x * mu.y - u.y * mu.x));
    }
  }
  return q;
}

}  // namespace

std::optional<std::vector<RangeResult>> moving_disc_integral(
    const CouplingTerm& term, const std::vector<std::vector<AnnularSector>>& masks, Vec2 center,
    double w, double tolerance, std::size_t max_segments) {
  if (term.n_gates != 0) return std::nullopt;
  Disc discs[kMaxDiscs];
  std::size_t n_fixed = 0;
  const MovingDisc* disc = nullptr;
  for (std::size_t i = 0; i < term.n_discs; ++i) {
    const MovingDisc& d = term.discs[i];
    if (d.scale != 0.0) {
      if (disc) return std::nullopt;  // two boundaries that move at different rates
      disc = &d;
    } else {
      if (n_fixed + 1 >= kMaxDiscs) return std::nullopt;
      discs[n_fixed++] = {d.shift, d.radius};
    }
  }
  if (!disc) return std::nullopt;

  const Vec2 mu = disc->scale * center + disc->shift;
  const double sigma = 0.5 * std::abs(disc->scale) * w, var = sigma * sigma, r = disc->radius;
  // The kernel is below exp(-50) of its peak beyond 10 sigma from r (a Gaussian in q about r when r >> sigma,
  // q exp(-q^2 / 2 sigma^2) when r << sigma).
  const double lo = std::max(0.0, r - 10.0 * sigma), hi = r + 10.0 * sigma;
  // The kernel's bump (width sigma about r when r >> sigma) gets its own pieces: one rule each, no bisection.
  std::vector<double> points{lo, hi, r - 5.0 * sigma, r, r + 5.0 * sigma};
  points.erase(std::remove_if(points.begin() + 2, points.end(),
                              [&](double q) { return !(q > lo && q < hi); }),
               points.end());
  for (const std::vector<AnnularSector>& sectors : masks)
    for (double q : kink_radii(discs, n_fixed, sectors, mu))
      if (q > lo && q < hi) points.push_back(q);
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());

  // Pieces in the kernel's tails whose whole contribution is bounded below a hundredth of the tolerance's share
  // are left out, their bound added to the error: Lambda <= min(pi q^2, the masks' area), exp(-x) I1(x) <=
  // min(1, x / 2), and the Gaussian factor is largest at the end nearest r.
  double mask_area = 0.0;
  for (const std::vector<AnnularSector>& sectors : masks)
    for (const AnnularSector& s : sectors)
      mask_area += 0.5 * std::min(s.span, 2.0 * kPi) * (s.outer * s.outer - s.inner * s.inner);
  auto piece_bound = [&](double a, double b) {
    const double d = std::clamp(r, a, b) - r;
    return std::abs(term.weight) * std::min(kPi * b * b, mask_area) * (r / var) *
           std::exp(-0.5 * d * d / var) * std::min(1.0, 0.5 * b * r / var) * (b - a);
  };
  const double negligible = 0.01 * tolerance / static_cast<double>(points.size());
  double trimmed = 0.0;
  std::size_t first = 0, last = points.size() - 1;
  while (last - first > 1 && piece_bound(points[first], points[first + 1]) < negligible)
    trimmed += piece_bound(points[first], points[first + 1]), ++first;
  while (last - first > 1 && piece_bound(points[last - 1], points[last]) < negligible)
    trimmed += piece_bound(points[last - 1], points[last]), --last;

  // Fixed discs centred on the aperture's centre (the aperture, a shadow in its plane) only cut the sectors'
  // outer radius: Lambda is then one disc's area per sector, by Green's theorem.
  bool centred = true;
  double cut = HUGE_VAL;
  for (std::size_t i = 0; i < n_fixed; ++i) {
    centred = centred && discs[i].center.x == 0.0 && discs[i].center.y == 0.0;
    cut = std::min(cut, discs[i].radius);
  }
  // Every mask's sectors in one list (owner[i]: the mask of sector i), cut to the fixed discs when centred.
  std::vector<AnnularSector> all;
  std::vector<std::size_t> owner;
  for (std::size_t k = 0; k < masks.size(); ++k)
    for (AnnularSector s : masks[k]) {
      if (centred) s.outer = std::min(s.outer, cut);
      if (!centred || s.outer > s.inner) {
        all.push_back(s);
        owner.push_back(k);
      }
    }
  DiscSectorAreas green(mu, centred ? all : std::vector<AnnularSector>{});
  std::vector<double> areas(all.size());
  auto integrand = [&](double q, double* out) {
    std::fill(out, out + masks.size(), 0.0);
    const double d = q - r, g = std::exp(-0.5 * d * d / var);
    if (g == 0.0) return;
    const double k = term.weight * (r / var * g * scaled_bessel_i1(q * r / var));
    if (centred) {
      green(q, areas.data());
    } else {
      discs[n_fixed] = {mu, q};
      for (std::size_t i = 0; i < all.size(); ++i)
        areas[i] = sector_intersection_area(discs, n_fixed + 1, all[i]);
    }
    for (std::size_t i = 0; i < all.size(); ++i) out[owner[i]] += k * areas[i];
  };
  const std::vector<QuadratureResult> results =
      integrate_many(integrand, masks.size(), points.data() + first, last - first + 1,
                     tolerance - trimmed, max_segments);
  std::vector<RangeResult> out;
  for (const QuadratureResult& q : results)
    out.push_back({q.value, q.error + trimmed, q.evaluations, q.converged});
  return out;
}

}  // namespace lidar_overlap::beam_integral
