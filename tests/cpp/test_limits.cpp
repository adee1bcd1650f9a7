// Limits and cancellation: an error inside the parallel range loop reaches the caller (no std::terminate),
// a CancelScope stops a long call, thread counts, the memory budget and physical scales are enforced
// before any work, and G leaving an engine is finite and within [0, 1].
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "check.hpp"
#include "lidar_overlap/lidar_overlap.hpp"
#include "core/checks.hpp"     // internal: the shared argument checks
#include "core/constants.hpp"

using namespace lidar_overlap;

namespace {

std::vector<double> ranges(std::size_t count, double from, double to) {
  std::vector<double> z(count);
  for (std::size_t i = 0; i < count; ++i) z[i] = from * std::pow(to / from, double(i) / double(count - 1));
  return z;
}

void error_inside_the_loop_reaches_the_caller() {
  LidarSystem s;
  s.detector.offset = {1e3, 0.0};  // the radial FO path needs millions of panels at every range
  for (int threads : {1, 2, 4})
    test::throws("radial FO panels, threads " + std::to_string(threads),
                 [&] { overlap_fo_radial(s, ranges(16, 50.0, 500.0), RadialFoOptions{8.0, threads}); }, "ranges[");
}

void cancel_scope_stops_a_call() {
  LidarSystem s;
  s.beam.tilt = {1e-4, 0.0};  // two-dimensional beam integrals: long enough to be cancelled mid-way
  std::atomic<int> asked{0};
  bool cancelled = false;
  try {
    CancelScope scope([&] { return ++asked >= 3; }, std::chrono::milliseconds(0));
    overlap_rt(s, ranges(400, 5.0, 3000.0), RtOptions{1e-7, 2, 4000});
  } catch (const Cancelled&) {
    cancelled = true;
  }
  test::that("Cancelled thrown once should_stop says so", cancelled);
  test::that("should_stop asked from the calling thread", asked.load() >= 3);

  struct Stop {};
  bool rethrown = false;
  try {
    // Two threads: under load the worker may finish every range before the caller takes one, so
    // parallel_for asks the caller's scope before its region (without that the check failed at random).
    CancelScope scope([]() -> bool { throw Stop{}; }, std::chrono::milliseconds(0));
    overlap_rt(s, ranges(50, 5.0, 3000.0), RtOptions{1e-6, 2, 4000});
  } catch (const Stop&) {
    rethrown = true;
  }
  test::that("an exception of should_stop is rethrown to the caller", rethrown);

  // Without a scope, and after one has ended, the same call runs to the end.
  const RtOverlap plain = overlap_rt(s, ranges(8, 5.0, 3000.0));
  test::that("no scope: a full curve", plain.overlap.size() == 8);
}

void threads_are_bounded() {
  LidarSystem s;
  test::throws("threads above max_threads", [&] { overlap_rt(s, {100.0}, RtOptions{1e-4, max_threads() + 1, 4000}); },
               "threads");
  test::throws("negative threads", [&] { overlap_rt(s, {100.0}, RtOptions{1e-4, -1, 4000}); }, "threads");
  test::that("max_threads at least 256", max_threads() >= 256);
}

void memory_budget() {
  const std::size_t before = max_memory();
  set_max_memory(std::size_t{1} << 20);  // 1 MiB: a 512^2 complex field (4 MiB) no longer fits
  test::throws("Field::gaussian beyond the budget", [] { Field::gaussian(355e-9, 1e-3, 512, 1e-5); }, "n = 512");
  LidarSystem s;
  test::throws("beam_grid beyond the budget", [&] { overlap_fo(s, {100.0}, FoOptions{512, 10.0, 4096, 1}); },
               "beam_grid");
  set_max_memory(0);
  test::that("0 restores the default", max_memory() == before);
  test::throws("grid side beyond kMaxGridSide", [] { Field::gaussian(355e-9, 1e-3, kMaxGridSide + 2, 1e-5); }, "n = ");
}

void physical_scales() {
  auto beam = [](double wavelength, double waist) {
    GaussianBeam b;
    b.wavelength = wavelength;
    b.waist_radius = waist;
    return b;
  };
  test::throws("wavelength 1e300", [&] { beam(1e300, 1e-3).validate(); }, "beam.wavelength");
  test::throws("waist 1e-300", [&] { beam(355e-9, 1e-300).validate(); }, "beam.waist_radius");
  test::throws("waist below lambda / pi", [&] { beam(355e-9, 1e-7).validate(); }, "beam.waist_radius");
  GaussianBeam narrow = beam(355e-9, 1e-3);
  narrow.divergence = 0.5 * 355e-9 / (kPi * 1e-3);
  test::throws("M^2 < 1 with the Gaussian law", [&] { narrow.validate(); }, "beam.divergence");
  narrow.width_law = WidthLaw::linear;
  narrow.validate();  // the paper's geometric marginal ray takes any divergence
  LidarSystem s;
  test::throws("range 5e-324", [&] { overlap_rt(s, {5e-324}); }, "ranges[0]");
  s.telescope.diameter = 5e-324;
  test::throws("diameter 5e-324 names the diameter", [&] { s.validate(); }, "telescope.diameter");
}

void overlap_values_are_checked() {
  std::vector<double> g{-1e-5, 0.5, 1.0 + 1e-5};
  checks::overlap_values(g, {1.0, 2.0, 3.0}, 1e-4, "test");
  test::that("round-off within the slack clipped into [0, 1]", g[0] == 0.0 && g[1] == 0.5 && g[2] == 1.0);
  for (double bad : {double(NAN), double(INFINITY), -1e-3, 1.01}) {
    std::vector<double> one{bad};
    bool refused = false;
    try {
      checks::overlap_values(one, {7.0}, 1e-4, "test");
    } catch (const std::domain_error& e) {
      refused = std::string(e.what()).find("ranges[0] = 7") != std::string::npos;
    }
    test::that("G = " + std::to_string(bad) + " refused, naming the range", refused);
  }
  test::that("saturate: NaN and huge values do not wrap", checks::saturate(NAN) == (std::size_t{1} << 62) &&
                                                                checks::saturate(1e300) == (std::size_t{1} << 62) &&
                                                                checks::saturate(-5.0) == 0 &&
                                                                checks::saturate(7.9) == 7);
}

}  // namespace

int main() {
  error_inside_the_loop_reaches_the_caller();
  cancel_scope_stops_a_call();
  threads_are_bounded();
  memory_budget();
  physical_scales();
  overlap_values_are_checked();
  return test::report("test_limits");
}
