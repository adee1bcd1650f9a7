#include "geometry/circles.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "core/constants.hpp"

namespace lidar_overlap {

namespace {

constexpr double kTwoPi = 2.0 * kPi;

// x - sin x without cancellation for small x (the thin segments of nearly tangent circles, or of a
// detector disc seen through a lens whose image is 10^7 times the aperture).
double x_minus_sin(double x) {
  if (std::abs(x) > 0.25) return x - std::sin(x);
  const double x2 = x * x;
  // Taylor series; the first omitted term is below 1e-17 of the sum for |x| <= 0.25.
  return x * x2 / 6.0 *
         (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0 * (1.0 - x2 / 110.0))));
}

// sin(h / 2) for the half-angle h, seen from its own centre, of the arc of circle (r) inside a circle (r_other)
// whose centre is d away (the circles cross). From the sagitta t = (r_other - d + r)(r_other + d - r) / (2 d),
// which has no cancellation, instead of acos((d^2 + r^2 - r_other^2) / (2 d r)), which loses all digits when
// the arc is short.
double arc_quarter_sine(double r, double r_other, double d) {
  const double t = (r_other - d + r) * (r_other + d - r) / (2.0 * d);
  return std::sqrt(std::clamp(t / (2.0 * r), 0.0, 1.0));
}

double arc_half_angle(double r, double r_other, double d) {
  return 2.0 * std::asin(arc_quarter_sine(r, r_other, d));
}

// The segment of a circle (r) whose arc has half-angle h = 2 asin(s): 1/2 r^2 (2h - sin 2h), with
// sin 2h = 2 sin h cos h = 4 s c (1 - 2 s^2) (c = sqrt(1 - s^2)) instead of a call to sin (the RT engine's
// lens areas take two per coupling; 20 % of a tilted Table 1 curve's time).
double segment_from_quarter_sine(double r, double s) {
  const double x = 4.0 * std::asin(s);  // 2h
  if (x <= 0.25) return 0.5 * r * r * x_minus_sin(x);
  const double c = std::sqrt((1.0 - s) * (1.0 + s));
  return 0.5 * r * r * (x - 4.0 * s * c * (1.0 - 2.0 * s * s));
}

// Angular intervals on a circle, kept as [start, end] with 0 <= start < end <= 2*pi relative to a
// reference angle. At most one interval per constraint plus one split, so a small fixed array does.
struct ArcSet {
  std::array<double, 2 * kMaxDiscs + 2> lo{}, hi{};
  std::size_t n = 0;
};

// Intersects `set` with the arc [a, a + len] (angles relative to the reference, a in [0, 2 pi)).
void intersect_arc(ArcSet& set, double a, double len) {
  ArcSet out;
  // The arc may wrap past 2 pi: it then also covers [a - 2 pi, a + len - 2 pi].
  const double starts[2] = {a, a - kTwoPi};
  for (std::size_t i = 0; i < set.n; ++i)
    for (double s : starts) {
      const double lo = std::max(set.lo[i], s), hi = std::min(set.hi[i], s + len);
      if (hi > lo) {
        out.lo[out.n] = lo;
        out.hi[out.n] = hi;
        ++out.n;
      }
    }
  set = out;
}

}  // namespace

double segment_area(double r, double half) { return 0.5 * r * r * x_minus_sin(2.0 * half); }

double lens_area(const Disc& a, const Disc& b) {
  const double d = norm(a.center - b.center);
  if (d >= a.radius + b.radius) return 0.0;
  const double rmin = std::min(a.radius, b.radius);
  if (d <= std::abs(a.radius - b.radius)) return kPi * rmin * rmin;
  // The lens is the two segments cut off by the common chord (Eq. B19 rearranged).
  return segment_from_quarter_sine(a.radius, arc_quarter_sine(a.radius, b.radius, d)) +
         segment_from_quarter_sine(b.radius, arc_quarter_sine(b.radius, a.radius, d));
}

double intersection_area(const Disc* discs, std::size_t n) {
  if (n == 0 || n > kMaxDiscs) throw std::invalid_argument("intersection_area: n must be in 1..6");
  for (std::size_t i = 0; i < n; ++i)
    if (discs[i].radius <= 0.0) return 0.0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (norm(discs[i].center - discs[j].center) >= discs[i].radius + discs[j].radius) return 0.0;

  // Drop every disc that contains another remaining one; of identical discs one is kept.
  std::array<bool, kMaxDiscs> dropped{};
  std::array<std::size_t, kMaxDiscs> keep{};
  std::size_t k = 0;
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t i = 0; i < n && !dropped[j]; ++i)
      if (i != j && !dropped[i] &&
          discs[j].radius >= norm(discs[i].center - discs[j].center) + discs[i].radius)
        dropped[j] = true;
  }
  for (std::size_t j = 0; j < n; ++j)
    if (!dropped[j]) keep[k++] = j;
  if (k == 1) return kPi * discs[keep[0]].radius * discs[keep[0]].radius;
  if (k == 2) return lens_area(discs[keep[0]], discs[keep[1]]);

  // Boundary of the intersection: on each circle, the arcs inside every other disc. Green's theorem
  // turns the area into a sum over those arcs, each giving its circular segment plus the triangle
  // (origin, arc start, arc end). The origin is the centre of the smallest disc, the scale of the result.
  std::size_t smallest = keep[0];
  for (std::size_t a = 1; a < k; ++a)
    if (discs[keep[a]].radius < discs[smallest].radius) smallest = keep[a];
  const Vec2 origin = discs[smallest].center;
  double area = 0.0;
  for (std::size_t a = 0; a < k; ++a) {
    const Disc& di = discs[keep[a]];
    ArcSet set;
    set.lo[0] = 0.0;
    set.hi[0] = kTwoPi;
    set.n = 1;
    double reference = 0.0;
    bool first = true;
    for (std::size_t b = 0; b < k && set.n > 0; ++b) {
      if (b == a) continue;
      const Disc& dj = discs[keep[b]];
      const Vec2 v = dj.center - di.center;
      const double d = norm(v);
      // Pairs here cross (no containment, no separation), so d > 0.
      const double half = arc_half_angle(di.radius, dj.radius, d);
      const double mid = std::atan2(v.y, v.x);
      if (first) {  // measure angles from the start of the first arc: it becomes [0, 2 half]
        reference = mid - half;
        set.hi[0] = 2.0 * half;
        first = false;
        continue;
      }
      double start = std::fmod(mid - half - reference, kTwoPi);
      if (start < 0.0) start += kTwoPi;
      intersect_arc(set, start, 2.0 * half);
    }
    const Vec2 c = di.center - origin;
    for (std::size_t s = 0; s < set.n; ++s) {
      const double t1 = reference + set.lo[s], t2 = reference + set.hi[s];
      const Vec2 p1 = c + di.radius * Vec2{std::cos(t1), std::sin(t1)};
      const Vec2 p2 = c + di.radius * Vec2{std::cos(t2), std::sin(t2)};
      area += segment_area(di.radius, 0.5 * (set.hi[s] - set.lo[s])) +
              0.5 * (p1.x * p2.y - p2.x * p1.y);
    }
  }
  return std::max(area, 0.0);
}

}  // namespace lidar_overlap
