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
      const double mid = std::atan2(circles[i].c.y, circles[i].c.x),
                   half = std::asin(circles[i].r / d);
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
    std::size_t lo_from = s.inner > 0.0 ? inner_index : nc,
                hi_from = outer_index;  // nc: the origin
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
    area -=
        swept(a, b, root_at(bottom, a, centred), root_at(bottom, b, centred), bottom.r, centred);
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
    for (double t :
         {s.start, s.start + s.span}) {  // the edge segments from inner to outer along angle t
      const Vec2 u{std::cos(t), std::sin(t)};
      const double along = std::clamp(dot(p, u), s.inner, s.outer);
      d = std::min(d, norm(p - along * u));
    }
  return d;
}

}  // namespace lidar_overlap
