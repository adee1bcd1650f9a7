// The turbulent FO path's split step (atmosphere/scaled_step.hpp, segment_plan.hpp, phasor.hpp):
// - along one cone of spacings, departing again from a plane reached and arriving further is the same
//   operator as arriving there at once (what lets one forward transform serve every plane of a segment);
// - the plan's spacings lie on that cone and end each segment on turbulent_grid's side;
// - phasors (two at a time) gives phasor's bits, and phasor is within 2.5e-16 of libm's cos and sin, for
//   ordinary and hostile phases.
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "atmosphere/phasor.hpp"
#include "atmosphere/scaled_step.hpp"
#include "atmosphere/segment_plan.hpp"
#include "check.hpp"

using namespace lidar_overlap;

namespace {

// Largest |a - b| over the grid, relative to the largest |b|.
double relative_difference(const Field& a, const Field& b) {
  double diff = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < a.values.size(); ++i) {
    diff = std::max(diff, std::abs(a.values[i] - b.values[i]));
    peak = std::max(peak, std::abs(b.values[i]));
  }
  return diff / peak;
}

void a_chain_along_the_cone_is_one_step() {
  const std::size_t n = 128;
  const double lambda = 532e-9, d = 1e-4, c = 1.0 / 40.0;  // spacing grows by 1 / 40 per m
  const double dz1 = 13.0, dz2 = 29.0;
  // A beam with some structure: an off-axis Gaussian with a tilt and a curvature.
  Field u = Field::gaussian(lambda, 2e-3, n, d, {3e-4, -2e-4});
  for (std::size_t iy = 0; iy < n; ++iy)
    for (std::size_t ix = 0; ix < n; ++ix) {
      const double x = u.coordinate(ix), y = u.coordinate(iy);
      u.values[iy * n + ix] *= std::polar(1.0, 900.0 * x - 400.0 * y + 2e5 * (x * x + y * y));
    }
  auto none = [](std::size_t, const Complex*) {};
  const detail::Departure leave(n, d, 0.0, c, lambda);
  Field spectrum = u;
  leave.execute(spectrum, nullptr, nullptr, nullptr);
  // At once: dz1 + dz2 from the spectrum.
  const detail::Arrival direct(n, d, dz1 + dz2, c, lambda);
  Field once = u;
  direct.execute(spectrum, once, &once, none);
  // In two steps: reach dz1, leave again along the same cone (the virtual source dz1 further behind).
  const detail::Arrival first(n, d, dz1, c, lambda);
  Field twice = u;
  first.execute(spectrum, twice, &twice, none);
  const double m1 = 1.0 + c * dz1;
  const detail::Departure again(n, first.spacing(), first.q3_curvature(), c / m1, lambda);
  again.execute(twice, nullptr, nullptr, nullptr);
  const detail::Arrival second(n, first.spacing(), dz2, c / m1, lambda);
  second.execute(twice, twice, &twice, none);
  test::near("spacing after two steps", twice.spacing / once.spacing, 1.0, 1e-14);
  test::near("field after two steps against one (relative)", relative_difference(twice, once), 0.0,
             1e-12);
  // Off the cone the second step is a different operator: the test can tell them apart.
  const detail::Departure off(n, first.spacing(), first.q3_curvature(), 2.0 * c / m1, lambda);
  Field other = u;
  first.execute(spectrum, other, &other, none);
  off.execute(other, nullptr, nullptr, nullptr);
  const detail::Arrival off_second(n, first.spacing(), dz2, 2.0 * c / m1, lambda);
  off_second.execute(other, other, &other, none);
  test::that("a step off the cone differs", relative_difference(other, once) > 1e-3);
}

void the_plan_follows_the_cones() {
  const std::vector<double> screens{100.0, 300.0}, ranges{50.0, 150.0, 300.0, 250.0, 400.0, 500.0};
  // Sides of the planes in plan order (screens first at equal range): 50, 100 (screen), 150, 250, 300
  // (screen), 300, 400, 500, on cones 0 -> 100, 100 -> 300 and 300 -> 500.
  const double pupil = 0.01;
  const std::vector<double> z{50.0, 100.0, 150.0, 250.0, 300.0, 300.0, 400.0, 500.0};
  auto cone = [](double za, double sa, double zb, double sb, double zi) {
    return sa + (sb - sa) * (zi - za) / (zb - za);
  };
  std::vector<double> windows;
  for (double zi : z)
    windows.push_back(zi <= 100.0   ? cone(0.0, pupil, 100.0, 0.05, zi)
                      : zi <= 300.0 ? cone(100.0, 0.05, 300.0, 0.08, zi)
                                    : cone(300.0, 0.08, 500.0, 0.2, zi));
  const std::size_t n = 64;
  const detail::TurbulentPlan plan =
      detail::plan_propagation(screens, ranges, windows, pupil, n, 355e-9);
  test::that("three segments", plan.segments.size() == 3);
  test::that("the segments leave from the transmitter and the two screens",
             plan.segments.size() == 3 && plan.segments[0].screen == -1 &&
                 plan.segments[1].screen == 0 && plan.segments[2].screen == 1);
  for (std::size_t q = 0; q < z.size(); ++q)
    test::near("plane " + std::to_string(q) + " spacing on its cone",
               plan.spacing[q] * double(n) / windows[q], 1.0, 1e-12);
  // Each segment ends with its screen (or the last range); the range at the screen's 300 m is read first.
  const std::vector<std::size_t>& middle = plan.segments[1].targets;
  test::that("the range at a screen's range arrives before the screen",
             middle.size() == 4 && plan.planes[middle[2]].range == 2 &&
                 plan.planes[middle[3]].screen == 1);
}

bool same_bits(Complex a, Complex b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void phasors_are_phasor() {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> wide(0.0, 40.0);
  std::vector<double> phase(4097);
  for (double& p : phase) p = wide(rng);
  const double nan = std::numeric_limits<double>::quiet_NaN(),
               inf = std::numeric_limits<double>::infinity();
  const double hostile[] = {0.0,
                            -0.0,
                            5e-324,
                            1e-300,
                            0.7853981633974483,
                            -0.7853981633974483,
                            1.5707963267948966,
                            3.141592653589793,
                            99999.99,
                            -1e5,
                            1e5 + 1.0,
                            1e300,
                            -1e300,
                            4294967296.0,
                            nan,
                            inf,
                            -inf};
  for (std::size_t i = 0; i < std::size(hostile); ++i) phase[3 * i + 1] = hostile[i];
  std::vector<Complex> table(phase.size());
  detail::phasors(phase.data(), table.data(), phase.size());  // odd count: the last one alone
  bool same = true;
  double worst = 0.0;
  for (std::size_t i = 0; i < phase.size(); ++i) {
    const Complex one = detail::phasor(phase[i]);
    same = same &&
           (same_bits(one, table[i]) || (std::isnan(one.real()) && std::isnan(table[i].real())));
    if (std::isfinite(phase[i]))
      worst = std::max(worst, std::abs(one - Complex(std::cos(phase[i]), std::sin(phase[i]))));
    else
      test::that("exp(i " + std::to_string(phase[i]) + ") is NaN",
                 std::isnan(one.real()) && std::isnan(one.imag()));
  }
  test::that("phasors gives phasor's bits", same);
  test::near("phasor against libm", worst, 0.0, 2.5e-16);
}

}  // namespace

int main() {
  a_chain_along_the_cone_is_one_step();
  the_plan_follows_the_cones();
  phasors_are_phasor();
  return test::failures;
}
