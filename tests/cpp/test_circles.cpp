// Disc intersection areas against closed forms and an independent grid count.
#include <algorithm>
#include <random>
#include <stdexcept>

#include "check.hpp"
#include "geometry/circles.hpp"

using namespace lidar_overlap;

namespace {
constexpr double kPi = 3.14159265358979323846;

// Fraction of a fine grid over the bounding box of disc 0 inside every disc (independent of arcs).
double grid_area(const Disc* d, std::size_t n, int cells) {
  const double r = d[0].radius, x0 = d[0].center.x - r, y0 = d[0].center.y - r, h = 2.0 * r / cells;
  long inside = 0;
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) {
      const Vec2 p{x0 + (i + 0.5) * h, y0 + (j + 0.5) * h};
      bool in = true;
      for (std::size_t k = 0; k < n && in; ++k) in = norm(p - d[k].center) <= d[k].radius;
      inside += in;
    }
  return inside * h * h;
}
}  // namespace

int main() {
  // Two equal unit discs at distance 1: lens area 2 pi/3 - sqrt(3)/2.
  const Disc a{{0, 0}, 1.0}, b{{1, 0}, 1.0};
  test::near("lens of two unit discs at distance 1", lens_area(a, b),
             2 * kPi / 3 - std::sqrt(3.0) / 2, 1e-14);
  test::near("disjoint", lens_area(a, {{2.5, 0}, 1.0}), 0.0, 0.0);
  test::near("contained", lens_area(a, {{0.2, 0.1}, 0.3}), kPi * 0.09, 1e-15);
  Disc ab[2] = {a, b};
  test::near("general routine on two discs", intersection_area(ab, 2), lens_area(a, b), 1e-14);
  // Identical discs, and a disc containing the other two.
  Disc same[3] = {a, a, {{0, 0}, 5.0}};
  test::near("identical discs", intersection_area(same, 3), kPi, 1e-14);
  // Three pairwise-overlapping discs with an empty common part.
  Disc empty[3] = {{{0, 0}, 1.0}, {{1.8, 0}, 1.0}, {{0.9, 1.6}, 1.0}};
  test::near("pairwise overlapping, no common point", intersection_area(empty, 3), 0.0, 0.0);

  // A small disc cut by huge ones (radius ratio 1e4, as a small aperture against a detector disc seen
  // through the lens near focus). Reference: the textbook acos form of Eq. (B19) in long double; its
  // cancellation leaves ~R^2 eps_ld / theta ~ 1e-15 m^2 absolute, so areas are compared to
  // 1e-6 pi r^2 (3e-14). The same acos form in double errs by ~1e-12 and would fail.
  auto lens_ld = [](long double r1, long double r2, long double d) {
    const long double c1 = (d * d + r1 * r1 - r2 * r2) / (2 * d * r1),
                      c2 = (d * d + r2 * r2 - r1 * r1) / (2 * d * r2);
    return r1 * r1 * std::acos(c1) + r2 * r2 * std::acos(c2) -
           0.5L * std::sqrt((-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2));
  };
  const double r = 1e-4, big = 1.0, pi_r2 = kPi * r * r, area_tolerance = 1e-6 * pi_r2;
  for (double frac : {0.3, -0.6, 0.99}) {
    const Disc small{{0, 0}, r}, keep_right{{big + frac * r, 0}, big};  // keeps x > frac r, nearly
    const double expected = static_cast<double>(lens_ld(r, big, big + frac * r));
    test::near("small disc against huge disc, h/r=" + std::to_string(frac),
               lens_area(small, keep_right), expected, area_tolerance);
    // A second huge disc keeping x < 0.7 r: the two removed caps are disjoint, so
    // area(small ∩ both) = lens(small, right) + lens(small, left) - pi r^2 (Green's-theorem path).
    const Disc keep_left{{0.7 * r - big, 0}, big};
    const double both = expected + static_cast<double>(lens_ld(r, big, big - 0.7 * r)) - pi_r2;
    Disc three[3] = {small, keep_right, keep_left};
    test::near("two huge discs cutting a small one, h/r=" + std::to_string(frac),
               intersection_area(three, 3), std::max(both, 0.0), area_tolerance);
  }

  // Random crossing pairs of comparable discs (segments of every half-angle, through the switch from the series
  // of x - sin x at 2h = 0.25 to the closed form) against the long-double acos form.
  std::mt19937_64 pair_rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst_pair = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const double r1 = 0.2 + unit(pair_rng), r2 = 0.2 + unit(pair_rng);
    const double d =
        std::abs(r1 - r2) + (0.001 + 0.998 * unit(pair_rng)) * (r1 + r2 - std::abs(r1 - r2));
    const double expected = static_cast<double>(lens_ld(r1, r2, d));
    worst_pair = std::max(worst_pair, std::abs(lens_area({{0, 0}, r1}, {{d, 0}, r2}) - expected));
  }
  test::near("random crossing pairs against the long-double acos form", worst_pair, 0.0, 1e-14);

  // Random triples and quadruples against a 1000x1000 grid count (area error ~ perimeter * h).
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> pos(-1.0, 1.0), rad(0.3, 1.5);
  for (int trial = 0; trial < 40; ++trial) {
    const std::size_t n = 3 + trial % 2;
    Disc d[4];
    for (std::size_t k = 0; k < n; ++k) d[k] = {{pos(rng), pos(rng)}, rad(rng)};
    const int cells = 1000;
    const double h = 2.0 * d[0].radius / cells;
    const double tolerance = 4.0 * 2.0 * kPi * 1.5 * h * (double)n;  // boundary cells only
    test::near("random discs vs grid, trial " + std::to_string(trial), intersection_area(d, n),
               grid_area(d, n, cells), tolerance);
  }
  test::throws(
      "too many discs",
      [] {
        Disc d[7]{};
        intersection_area(d, 7);
      },
      "n must be");
  return test::report("test_circles");
}
