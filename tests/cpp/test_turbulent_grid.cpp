// The turbulent FO path's grid rule (atmosphere/turbulent_grid.hpp): overlap_fo_turbulent accepts exactly the
// beam_grid turbulent_grid states as the least on both paths and refuses the even size below it, naming the
// size; the windows never shrink; transmit needs no more than the floor; bad options are refused by name.
#include <limits>
#include <string>
#include <vector>

#include "check.hpp"
#include "small_lidar.hpp"
#include "lidar_overlap/atmosphere/overlap_turbulent.hpp"
#include "lidar_overlap/atmosphere/turbulent_grid.hpp"

using namespace lidar_overlap;

namespace {

// D = 5 cm, f = 0.5 m, a field of view of 0.36 mrad at 1064 nm through Cn2 = 1e-14 over 300 m: a least grid
// between 64 and 256, so that both sides of it run in well under a second.
LidarSystem small_lidar() { return test::small_lidar(90e-6); }

TurbulenceOptions both(std::size_t grid) {
  TurbulenceOptions o;
  o.realizations = 1;
  o.threads = 1;
  o.screens = 2;
  o.beam_grid = grid;
  o.receiver_fields = 1;
  o.paths = TurbulencePaths::both;
  return o;
}

void least_grid_is_the_core_threshold() {
  const std::vector<double> z{150.0, 300.0};
  const Cn2Profile air = Cn2Profile::constant(1e-14);
  const TurbulentGrid g = turbulent_grid(small_lidar(), z, air, both(0));
  const std::size_t n = g.min_beam_grid;
  test::that("the least grid is even and within [64, 256]: " + std::to_string(n),
             n % 2 == 0 && n >= 64 && n <= 256);
  test::that("four planes (two screens, two ranges)",
             g.window.size() == 4 && g.plane_range.size() == 4);
  bool grows = g.window.front() >= g.pupil_window;
  for (std::size_t i = 1; i < g.window.size(); ++i) grows = grows && g.window[i] >= g.window[i - 1];
  test::that("the windows never shrink along the path", grows);
  bool accepted = true;
  try {
    overlap_fo_turbulent(small_lidar(), z, air, both(n));
  } catch (const std::exception&) {
    accepted = false;
  }
  test::that("the least grid runs", accepted);
  test::throws(
      "two samples fewer", [&] { overlap_fo_turbulent(small_lidar(), z, air, both(n - 2)); },
      ">= " + std::to_string(n));
  TurbulenceOptions transmit = both(0);
  transmit.paths = TurbulencePaths::transmit;
  test::that("transmit needs the floor only",
             turbulent_grid(small_lidar(), z, air, transmit).min_beam_grid == 32);
}

void bad_options() {
  const std::vector<double> z{300.0};
  const Cn2Profile air = Cn2Profile::constant(1e-14);
  TurbulenceOptions o = both(0);
  o.screens = 0;
  test::throws("no screens", [&] { turbulent_grid(small_lidar(), z, air, o); }, "screens");
  o = both(0);
  o.beam_window = std::numeric_limits<double>::quiet_NaN();
  test::throws("a NaN window", [&] { turbulent_grid(small_lidar(), z, air, o); }, "beam_window");
  test::throws(
      "a negative range", [&] { turbulent_grid(small_lidar(), {-1.0}, air, both(0)); },
      "ranges[0]");
}

}  // namespace

int main() {
  least_grid_is_the_core_threshold();
  bad_options();
  return test::report("test_turbulent_grid");
}
