// The turbulent FO overlap with both paths (TurbulencePaths::both): without turbulence its mean is the
// turbulence-free overlap within the random-phase receiver's stated noise; transmit-only runs are unchanged by
// the option; rows are bit for bit the same on any thread count and in any split of the run; bad options are
// refused by name.
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "check.hpp"
#include "small_lidar.hpp"
#include "lidar_overlap/atmosphere/overlap_turbulent.hpp"

using namespace lidar_overlap;

namespace {

// A small coaxial lidar at 1064 nm: D = 5 cm, f = 0.5 m, w0 = 5 mm, a field of view of 4 diffraction widths.
LidarSystem small_lidar() { return test::small_lidar(45e-6); }

TurbulenceOptions both(std::size_t realizations, int threads) {
  TurbulenceOptions o;
  o.realizations = realizations;
  o.threads = threads;
  o.screens = 3;
  o.beam_grid = 128;
  o.seed = 7;
  o.paths = TurbulencePaths::both;
  return o;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

double mean(const std::vector<std::vector<double>>& rows, std::size_t i) {
  double s = 0.0;
  for (const auto& r : rows) s += r[i];
  return s / static_cast<double>(rows.size());
}

double standard_error(const std::vector<std::vector<double>>& rows, std::size_t i) {
  const double m = mean(rows, i);
  double s = 0.0;
  for (const auto& r : rows) s += (r[i] - m) * (r[i] - m);
  return std::sqrt(s / static_cast<double>(rows.size() - 1) / static_cast<double>(rows.size()));
}

// Without turbulence both paths reduce to the plain overlap: the random-phase sensitivity is unbiased, its
// speckle noise averages over the realisations. 4 standard errors, plus 2e-3 for the shared grid's sampling
// of the aperture's edge (the plain path integrates the exact pupil OTF).
void calm_air_is_the_plain_overlap() {
  const std::vector<double> z{200.0, 1000.0};
  const Cn2Profile calm = Cn2Profile::constant(0.0);
  TurbulenceOptions tx = both(1, 0);
  tx.paths = TurbulencePaths::transmit;
  const TurbulentOverlap plain = overlap_fo_turbulent(small_lidar(), z, calm, tx);
  const TurbulentOverlap g = overlap_fo_turbulent(small_lidar(), z, calm, both(40, 0));
  for (std::size_t i = 0; i < z.size(); ++i) {
    const double se = standard_error(g.overlap, i);
    std::cout << "calm air at " << z[i] << " m: both paths " << mean(g.overlap, i) << " +- " << se
              << ", plain " << plain.overlap[0][i] << "\n";
    test::near("calm air, both paths = plain at " + std::to_string(z[i]) + " m", mean(g.overlap, i),
               plain.overlap[0][i], 4.0 * se + 2e-3);
    test::near("calm air, uncorrelated = plain at " + std::to_string(z[i]) + " m",
               mean(g.uncorrelated, i), plain.overlap[0][i],
               4.0 * standard_error(g.uncorrelated, i) + 2e-3);
  }
  test::that("transmit-only leaves uncorrelated empty", plain.uncorrelated.empty());
}

// The option does not touch transmit-only runs: an explicit transmit equals the default-constructed run.
void transmit_is_unchanged() {
  const std::vector<double> z{300.0, 800.0};
  const Cn2Profile air = Cn2Profile::constant(3e-14);
  TurbulenceOptions o = both(3, 1);
  o.paths = TurbulencePaths::transmit;
  TurbulenceOptions d;
  d.realizations = 3, d.threads = 1, d.screens = 3, d.beam_grid = 128, d.seed = 7;
  const TurbulentOverlap a = overlap_fo_turbulent(small_lidar(), z, air, o),
                         b = overlap_fo_turbulent(small_lidar(), z, air, d);
  bool ok = true;
  for (std::size_t k = 0; k < 3; ++k)
    for (std::size_t i = 0; i < z.size(); ++i)
      ok = ok && same_bits(a.overlap[k][i], b.overlap[k][i]);
  test::that("paths = transmit is the default run bit for bit", ok);
}

// Rows of a part against the whole run, bit for bit, for splits inside a pair and on 1 or 2 threads.
void parts_equal_the_whole() {
  const std::vector<double> z{300.0, 600.0};
  const Cn2Profile air = Cn2Profile::constant(1e-14);
  TurbulenceOptions o = both(5, 2);
  o.receiver_fields = 2;
  const TurbulentOverlap whole = overlap_fo_turbulent(small_lidar(), z, air, o);
  for (int threads : {1, 2})
    for (std::size_t first : {0, 1, 3}) {
      TurbulenceOptions p = o;
      p.threads = threads;
      p.first_realization = first;
      p.realizations = first == 3 ? 2 : 1;
      const TurbulentOverlap part = overlap_fo_turbulent(small_lidar(), z, air, p);
      bool ok = true;
      for (std::size_t r = 0; r < part.overlap.size(); ++r)
        for (std::size_t i = 0; i < z.size(); ++i)
          ok = ok && same_bits(part.overlap[r][i], whole.overlap[first + r][i]) &&
               same_bits(part.uncorrelated[r][i], whole.uncorrelated[first + r][i]) &&
               same_bits(part.wander_x[r], whole.wander_x[first + r]);
      test::that("both paths: rows from " + std::to_string(first) + " on " +
                     std::to_string(threads) + " threads equal the whole run's",
                 ok);
    }
  test::that("the draws differ", whole.overlap[0][1] != whole.overlap[1][1]);
}

void bad_options() {
  const std::vector<double> z{500.0};
  const Cn2Profile air = Cn2Profile::constant(1e-14);
  TurbulenceOptions o = both(1, 1);
  o.receiver_fields = 0;
  test::throws(
      "no receiver fields", [&] { overlap_fo_turbulent(small_lidar(), z, air, o); },
      "receiver_fields");
  o = both(1, 1);
  o.paths = static_cast<TurbulencePaths>(7);
  test::throws("unknown paths", [&] { overlap_fo_turbulent(small_lidar(), z, air, o); }, "paths");
  LidarSystem fibre = small_lidar();
  fibre.detector.numerical_aperture = 0.1;
  test::throws(
      "a fibre NA", [&] { overlap_fo_turbulent(fibre, z, air, both(1, 1)); }, "numerical_aperture");
  // Table 1's 0.9 mrad field of view at 355 nm through a 15 cm aperture needs ~500 samples per side.
  o = both(1, 1);
  test::throws(
      "a grid too coarse for the field of view",
      [&] { overlap_fo_turbulent(LidarSystem{}, z, air, o); }, "beam_grid");
}

}  // namespace

int main() {
  calm_air_is_the_plain_overlap();
  transmit_is_unchanged();
  parts_equal_the_whole();
  bad_options();
  return test::report("test_turbulent_return");
}
