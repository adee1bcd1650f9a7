#include "lidar_overlap/circles.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace lidar_overlap {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;

// Area of the circular segment of a disc of radius r cut by a chord at signed distance h from
// its centre (h in [-r, r]): the part on the far side of the chord.
double segment_area(double r, double h) {
  const double c = std::clamp(h / r, -1.0, 1.0);
  return r * r * std::acos(c) - h * std::sqrt(std::max(0.0, r * r - h * h));
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

double lens_area(const Disc& a, const Disc& b) {
  const double d = norm(a.center - b.center);
  if (d >= a.radius + b.radius) return 0.0;
  const double rmin = std::min(a.radius, b.radius);
  if (d <= std::abs(a.radius - b.radius)) return kPi * rmin * rmin;
  // Distance from each centre to the common chord; the lens is the two segments beyond it.
  const double ha = (d * d + a.radius * a.radius - b.radius * b.radius) / (2.0 * d);
  const double hb = d - ha;
  return segment_area(a.radius, ha) + segment_area(b.radius, hb);
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
  // turns the area into a sum over those arcs. Coordinates are taken relative to the first disc to
  // keep the terms small.
  const Vec2 origin = discs[keep[0]].center;
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
      // Pairs here cross (no containment, no separation), so d > 0 and the cosine is in [-1, 1].
      const double c = (d * d + di.radius * di.radius - dj.radius * dj.radius) / (2.0 * d * di.radius);
      const double half = std::acos(std::clamp(c, -1.0, 1.0));
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
      area += 0.5 * (di.radius * di.radius * (t2 - t1) +
                     di.radius * c.x * (std::sin(t2) - std::sin(t1)) -
                     di.radius * c.y * (std::cos(t2) - std::cos(t1)));
    }
  }
  return std::max(area, 0.0);
}

}  // namespace lidar_overlap
