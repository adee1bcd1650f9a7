// The turbulent FO overlap in parts: realisations [first, first + count) of a run (TurbulenceOptions::
// first_realization) are bit for bit the same rows of the whole run, for parts that start or end inside a pair
// of screens, on one thread or several; first_realization out of its range is refused by name, without
// wrapping around.
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "check.hpp"
#include "lidar_overlap/atmosphere/overlap_turbulent.hpp"

using namespace lidar_overlap;

namespace {

const std::vector<double> kRanges{400.0, 1000.0};
const Cn2Profile kAtmosphere = Cn2Profile::constant(2e-14);

TurbulenceOptions options(std::size_t first, std::size_t count, int threads) {
  TurbulenceOptions o;
  o.first_realization = first;
  o.realizations = count;
  o.threads = threads;
  o.screens = 3;
  o.beam_grid = 64;
  o.seed = 12345;
  return o;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Rows of `part` against rows first, first + 1, ... of `whole`: G at every range, wander and radius.
void same_rows(const std::string& what, const TurbulentOverlap& whole, const TurbulentOverlap& part,
               std::size_t first) {
  bool ok = part.overlap.size() == part.wander_x.size() &&
            first + part.overlap.size() <= whole.overlap.size();
  for (std::size_t r = 0; ok && r < part.overlap.size(); ++r) {
    const std::size_t k = first + r;
    ok = part.overlap[r].size() == kRanges.size() &&
         same_bits(part.wander_x[r], whole.wander_x[k]) &&
         same_bits(part.wander_y[r], whole.wander_y[k]) &&
         same_bits(part.radius_last[r], whole.radius_last[k]);
    for (std::size_t i = 0; ok && i < kRanges.size(); ++i)
      ok = same_bits(part.overlap[r][i], whole.overlap[k][i]);
  }
  test::that(what + ": rows equal the whole run's bit for bit", ok);
}

void parts_equal_the_whole() {
  const std::size_t count = 7;
  const TurbulentOverlap whole =
      overlap_fo_turbulent(LidarSystem{}, kRanges, kAtmosphere, options(0, count, 2));
  test::that("the draws differ", whole.overlap[0][0] != whole.overlap[1][0] &&
                                     whole.overlap[1][0] != whole.overlap[6][0]);
  same_rows("one thread", whole,
            overlap_fo_turbulent(LidarSystem{}, kRanges, kAtmosphere, options(0, count, 1)), 0);
  // Splits at even and odd indices: [0, 3) [3, 4) [4, 7) and [0, 1) [1, 6) [6, 7), each part on 1 and 2 threads.
  for (const std::vector<std::size_t>& cuts :
       {std::vector<std::size_t>{0, 3, 4, 7}, std::vector<std::size_t>{0, 1, 6, 7}})
    for (int threads : {1, 2})
      for (std::size_t j = 0; j + 1 < cuts.size(); ++j) {
        const std::size_t first = cuts[j], n = cuts[j + 1] - cuts[j];
        same_rows(
            "[" + std::to_string(first) + ", " + std::to_string(first + n) + ") on " +
                std::to_string(threads) + " threads",
            whole,
            overlap_fo_turbulent(LidarSystem{}, kRanges, kAtmosphere, options(first, n, threads)),
            first);
      }
}

void first_realization_bounds() {
  const std::size_t max = kMaxRealizations, size_max = std::numeric_limits<std::size_t>::max();
  for (std::size_t first : {max - 1, max, size_max - 1, size_max})
    test::throws(
        "first + realizations beyond the run's bound (" + std::to_string(first) + ")",
        [&] { overlap_fo_turbulent(LidarSystem{}, kRanges, kAtmosphere, options(first, 2, 1)); },
        "first_realization");
  test::throws(
      "the message gives the valid range",
      [&] { overlap_fo_turbulent(LidarSystem{}, kRanges, kAtmosphere, options(max, 1, 1)); },
      "from 0 to 999999");
  // At the bound itself: the last realisation of the longest run (its screens from pair 499999).
  TurbulenceOptions last = options(max - 1, 1, 1);
  last.screens = 1;
  last.beam_grid = 32;
  const TurbulentOverlap g = overlap_fo_turbulent(LidarSystem{}, {1000.0}, kAtmosphere, last);
  test::that("the last realisation of the longest run",
             g.overlap.size() == 1 && g.overlap[0][0] > 0.0);
}

}  // namespace

int main() {
  parts_equal_the_whole();
  first_realization_bounds();
  return test::report("test_turbulent_parts");
}
