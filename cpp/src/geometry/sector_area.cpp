#include "geometry/sector_area.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "core/constants.hpp"

namespace lidar_overlap {

namespace {

constexpr double kTwoPi = 2.0 * kPi;
// Pieces are cut to at most this angle, so that an arc piece spans less than pi about its own centre
// (at most twice the angle seen from an origin inside the disc): its chord then fixes it.
constexpr double kMaxPiece = 0.25 * kPi;

// A boundary circle: a disc (the region is inside), the sector's outer arc (inside, centred at the origin)
// or its inner arc (outside, centred at the origin).
struct Circle {
  Vec2 c;
  double r;
};

// Radii along direction u where |rho u - c| = r: near and far root (false when the ray misses).
bool roots(const Circle& k, Vec2 u, double& near, double& far) {
  const double b = dot(u, k.c), q = dot(k.c, k.c) - k.r * k.r;
  const double disc = b * b - q;
  if (disc < 0.0) return false;
  const double s = std::sqrt(disc);
  far = b + s;
  near = far > 0.0 ? q / far : b - s;  // stable: near * far = q
  return true;
}

// One end of a piece: the radius of circle k's near or far root at angle t (tangent rays clamp to the
// double root).
double root_at(const Circle& k, double t, bool far) {
  const Vec2 u{std::cos(t), std::sin(t)};
  const double b = dot(u, k.c), q = dot(k.c, k.c) - k.r * k.r;
  const double s = std::sqrt(std::max(0.0, b * b - q));
  if (far) return b + s;
  return b + s > 0.0 ? std::max(0.0, q / (b + s)) : std::max(0.0, b - s);
}

// Area swept from the origin over [a, b] up to an arc of radius r whose ends are at radii ra and rb:
// the triangle plus the segment when the arc bulges away from the origin, minus it when towards.
double swept(double a, double b, double ra, double rb, double r, bool bulges_away) {
  const Vec2 pa = ra * Vec2{std::cos(a), std::sin(a)}, pb = rb * Vec2{std::cos(b), std::sin(b)};
  const double triangle = 0.5 * ra * rb * std::sin(b - a);
  const double half = std::asin(std::min(1.0, 0.5 * norm(pb - pa) / r));
  const double seg = segment_area(r, half);
  return triangle + (bulges_away ? seg : -seg);
}

// Angle t mapped into [start, start + 2 pi).
double wrap(double t, double start) {
  double x = std::fmod(t - start, kTwoPi);
  if (x < 0.0) x += kTwoPi;
  return start + x;
}

}  // namespace

double sector_intersection_area(const Disc* discs, std::size_t n, const AnnularSector& s) {
  if (n > kMaxDiscs) throw std::invalid_argument("sector_intersection_area: n must be at most 6");
  // Discs: drop those containing the outer disc of the sector; a disc missing the annulus leaves nothing.
  std::array<Circle, kMaxDiscs + 2> circles;
  std::size_t nd = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = norm(discs[i].center), r = discs[i].radius;
    if (!(r > 0.0) || d >= r + s.outer || d + r <= s.inner) return 0.0;
    if (d + s.outer <= r) continue;
    circles[nd++] = {discs[i].center, r};
  }
  const std::size_t outer_index = nd, inner_index = nd + 1;
  circles[outer_index] = {{0.0, 0.0}, s.outer};
  circles[inner_index] = {{0.0, 0.0}, s.inner};
  const std::size_t nc = s.inner > 0.0 ? nd + 2 : nd + 1;

  // Breakpoints: the sector's edges and cuts every kMaxPiece, the tangents from the origin to each disc and
  // its centre's direction, and the angles of the crossings of every two circles.
  const double end = s.start + s.span;
  std::array<double, 2 + 9 + 3 * kMaxDiscs + (kMaxDiscs + 2) * (kMaxDiscs + 1)> t{};
  std::size_t nt = 0;
  auto add = [&](double angle) {
    const double a = wrap(angle, s.start);
    if (a > s.start && a < end) t[nt++] = a;
  };
  t[nt++] = s.start;
  t[nt++] = end;
  for (double a = s.start + kMaxPiece; a < end; a += kMaxPiece) t[nt++] = a;
  // A disc that leaves out the origin: its far arc between the tangents spans more than pi about its own
  // centre, so it is also cut at the centre's direction (each half then spans less than pi).
  for (std::size_t i = 0; i < nd; ++i) {
    const double d = norm(circles[i].c);
    if (d > circles[i].r) {
      const double mid = std::atan2(circles[i].c.y, circles[i].c.x), half = std::asin(circles[i].r / d);
      add(mid - half);
      add(mid);
      add(mid + half);
    }
  }
  for (std::size_t i = 0; i < nc; ++i)
    for (std::size_t j = i + 1; j < nc; ++j) {
      const Vec2 v = circles[j].c - circles[i].c;
      const double d = norm(v), ri = circles[i].r, rj = circles[j].r;
      if (!(d > 0.0) || d >= ri + rj || d <= std::abs(ri - rj)) continue;
      const double along = 0.5 * (d * d + ri * ri - rj * rj) / d;
      const double h = std::sqrt(std::max(0.0, ri * ri - along * along));
      const Vec2 e = (1.0 / d) * v, base = circles[i].c + along * e, perp{-e.y, e.x};
      for (double sign : {-1.0, 1.0}) {
        const Vec2 p = base + (sign * h) * perp;
        if (p.x != 0.0 || p.y != 0.0) add(std::atan2(p.y, p.x));
      }
    }
  std::sort(t.begin(), t.begin() + nt);

  // On each piece, the active lower and upper bounds at its middle hold throughout.
  double area = 0.0;
  for (std::size_t p = 0; p + 1 < nt; ++p) {
    const double a = t[p], b = t[p + 1];
    if (!(b > a)) continue;
    const double m = 0.5 * (a + b);
    const Vec2 u{std::cos(m), std::sin(m)};
    double lo = s.inner, hi = s.outer;
    std::size_t lo_from = s.inner > 0.0 ? inner_index : nc, hi_from = outer_index;  // nc: the origin
    bool empty = false;
    for (std::size_t i = 0; i < nd && !empty; ++i) {
      double near, far;
      if (!roots(circles[i], u, near, far) || far <= 0.0) {
        empty = true;
        break;
      }
      if (near > lo) lo = near, lo_from = i;
      if (far < hi) hi = far, hi_from = i;
    }
    if (empty || hi <= lo) continue;
    const Circle& top = circles[hi_from];
    area += swept(a, b, root_at(top, a, true), root_at(top, b, true), top.r, true);
    if (lo_from == nc) continue;  // the origin: nothing below
    const Circle& bottom = circles[lo_from];
    const bool centred = lo_from == inner_index;  // the inner arc bulges away from the origin
    area -= swept(a, b, root_at(bottom, a, centred), root_at(bottom, b, centred), bottom.r, centred);
  }
  return std::max(area, 0.0);
}

namespace {

// Length (rad) of the intersection of the arcs [a, a + la] and [b, b + lb] of one circle (la, lb in [0, 2 pi]).
double arc_overlap(double a, double la, double b, double lb) {
  double d = std::fmod(b - a, kTwoPi);
  if (d < 0.0) d += kTwoPi;  // [d, d + lb] and [d - 2 pi, d - 2 pi + lb] against [0, la]
  return std::max(0.0, std::min(la, d + lb) - d) + std::max(0.0, std::min(la, d - kTwoPi + lb));
}

// Angle (rad) of the circle of radius rho about the origin inside disc(mu, q), as an arc [start, start + length].
struct Arc {
  double start, length;
};
Arc circle_inside_disc(double rho, Vec2 mu, double m, double q) {
  if (m == 0.0) return {0.0, rho <= q ? kTwoPi : 0.0};
  const double c = (rho * rho + m * m - q * q) / (2.0 * rho * m);
  if (c <= -1.0) return {0.0, kTwoPi};
  if (c >= 1.0) return {0.0, 0.0};
  const double half = std::acos(c);
  return {std::atan2(mu.y, mu.x) - half, 2.0 * half};
}

// A point of the disc's circle: its angle psi about mu and the unit vector (cos psi, sin psi).
struct OnCircle {
  double psi;
  Vec2 e;
};

}  // namespace

double disc_sector_area(Vec2 mu, double q, const AnnularSector& s) {
  if (!(q > 0.0)) return 0.0;
  const double m = norm(mu), a = s.inner, b = s.outer;
  if (m >= q + b || m + q <= a) return 0.0;
  const bool full_turn = s.span >= kTwoPi;
  const double span = std::min(s.span, kTwoPi);
  // The sector's circles: 1/2 rho^2 per radian of their arcs inside the disc and the wedge (the inner one is
  // run clockwise).
  const Arc outer = circle_inside_disc(b, mu, m, q);
  double area = 0.5 * b * b * arc_overlap(outer.start, outer.length, s.start, span);
  if (a > 0.0) {
    const Arc inner = circle_inside_disc(a, mu, m, q);
    area -= 0.5 * a * a * arc_overlap(inner.start, inner.length, s.start, span);
  }
  if (m == 0.0) return area + (a <= q && q <= b ? 0.5 * q * q * span : 0.0);

  // The disc's circle mu + q e(psi) lies in the annulus where cos(psi - phi_mu) is in [c_a, c_b].
  const double c_b = (b * b - m * m - q * q) / (2.0 * m * q), c_a = (a * a - m * m - q * q) / (2.0 * m * q);
  if (c_b < -1.0 || c_a > 1.0) return area;
  const double cos_lo = std::min(1.0, c_b), cos_hi = std::max(-1.0, c_a);  // cos of delta_lo, delta_hi
  const double delta_lo = std::acos(cos_lo), delta_hi = std::acos(cos_hi);
  if (!(delta_hi > delta_lo)) return area;
  const Vec2 u_mu = (1.0 / m) * mu;
  const double phi_mu = std::atan2(mu.y, mu.x);
  auto at = [&](double delta, double cos_delta) {  // the point at psi = phi_mu + delta (delta in [-pi, pi])
    const double sin_delta = std::copysign(std::sqrt(std::max(0.0, 1.0 - cos_delta * cos_delta)), delta);
    return OnCircle{phi_mu + delta, {cos_delta * u_mu.x - sin_delta * u_mu.y, cos_delta * u_mu.y + sin_delta * u_mu.x}};
  };
  // Green's theorem on the arc [p1, p2]: 1/2 int (x dy - y dx) = 1/2 [q^2 psi + q (mu_x sin psi - mu_y cos psi)].
  auto arc_term = [&](const OnCircle& p1, const OnCircle& p2) {
    return 0.5 * (q * q * (p2.psi - p1.psi) + q * (mu.x * (p2.e.y - p1.e.y) - mu.y * (p2.e.x - p1.e.x)));
  };
  const OnCircle arcs[2][2] = {{at(-delta_hi, cos_hi), at(-delta_lo, cos_lo)}, {at(delta_lo, cos_lo), at(delta_hi, cos_hi)}};
  if (full_turn) return area + arc_term(arcs[0][0], arcs[0][1]) + arc_term(arcs[1][0], arcs[1][1]);

  // The wedge: where the circle crosses its two edge rays, and whether a point lies within it.
  const Vec2 u1{std::cos(s.start), std::sin(s.start)}, u2{std::cos(s.start + span), std::sin(s.start + span)};
  auto in_wedge = [&](Vec2 p) {
    const double after_start = u1.x * p.y - u1.y * p.x, before_end = p.x * u2.y - p.y * u2.x;
    return span <= kPi ? (after_start >= 0.0 && before_end >= 0.0) : (after_start >= 0.0 || before_end >= 0.0);
  };
  OnCircle crossings[4];
  std::size_t n_cross = 0;
  for (const Vec2& u : {u1, u2}) {
    const double along = dot(u, mu), off = u.x * mu.y - u.y * mu.x, h2 = q * q - off * off;
    if (h2 <= 0.0) continue;
    for (double sign : {-1.0, 1.0}) {
      const double t = along + sign * std::sqrt(h2);
      if (!(t > 0.0)) continue;
      const Vec2 e = (1.0 / q) * (t * u - mu);
      crossings[n_cross++] = {std::atan2(e.y, e.x), e};
    }
  }
  for (const auto& arc : arcs) {
    OnCircle points[6] = {arc[0]};
    std::size_t n = 1;
    for (std::size_t k = 0; k < n_cross; ++k) {  // crossings inside the arc, at their angle unwrapped into it
      OnCircle c = crossings[k];
      c.psi = arc[0].psi + std::fmod(std::fmod(c.psi - arc[0].psi, kTwoPi) + kTwoPi, kTwoPi);
      if (c.psi > arc[0].psi && c.psi < arc[1].psi) points[n++] = c;
    }
    std::sort(points + 1, points + n, [](const OnCircle& x, const OnCircle& y) { return x.psi < y.psi; });
    points[n++] = arc[1];
    for (std::size_t k = 0; k + 1 < n; ++k) {
      const double mid = 0.5 * (points[k].psi + points[k + 1].psi);
      if (in_wedge(mu + q * Vec2{std::cos(mid), std::sin(mid)})) area += arc_term(points[k], points[k + 1]);
    }
  }
  return std::max(area, 0.0);
}

bool sector_contains(const AnnularSector& s, Vec2 p) {
  const double rho = norm(p);
  if (rho < s.inner || rho > s.outer) return false;
  return s.span >= kTwoPi || wrap(std::atan2(p.y, p.x), s.start) - s.start <= s.span;
}

double sector_boundary_distance(const AnnularSector& s, Vec2 p) {
  const double rho = norm(p);
  double d = std::abs(rho - s.outer);
  if (s.inner > 0.0) d = std::min(d, std::abs(rho - s.inner));
  if (s.span < kTwoPi)
    for (double t : {s.start, s.start + s.span}) {  // the edge segments from inner to outer along angle t
      const Vec2 u{std::cos(t), std::sin(t)};
      const double along = std::clamp(dot(p, u), s.inner, s.outer);
      d = std::min(d, norm(p - along * u));
    }
  return d;
}

}  // namespace lidar_overlap
