// Limits and cancellation: an error inside the parallel range loop reaches the caller (no std::terminate),
// a CancelScope stops a long call (a single iteration on another thread, a transform pass), thread counts,
// the memory budget and physical scales are enforced before any work, and G leaving an engine is finite
// and within [0, 1].
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>
#include <vector>

#include "check.hpp"
#include "lidar_overlap/lidar_overlap.hpp"
#include "core/checks.hpp"  // internal: the shared argument checks
#include "core/constants.hpp"
#include "core/parallel.hpp"       // internal: parallel_for, cancellation_point
#include "fourier/fft_passes.hpp"  // internal: the passes of a 2-D transform

using namespace lidar_overlap;

namespace {

std::vector<double> ranges(std::size_t count, double from, double to) {
  std::vector<double> z(count);
  for (std::size_t i = 0; i < count; ++i)
    z[i] = from * std::pow(to / from, double(i) / double(count - 1));
  return z;
}

void error_inside_the_loop_reaches_the_caller() {
  LidarSystem s;
  s.detector.offset = {1e3, 0.0};  // the radial FO path needs millions of panels at every range
  for (int threads : {1, 2, 4})
    test::throws(
        "radial FO panels, threads " + std::to_string(threads),
        [&] { overlap_fo_radial(s, ranges(16, 50.0, 500.0), RadialFoOptions{8.0, threads}); },
        "ranges[");
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

// One iteration on two threads: it may go to the other thread, which has no CancelScope; the calling
// thread, out of iterations, keeps asking its scope. Before it did, such a call ran to its end.
void a_lone_iteration_on_another_thread_is_cancelled() {
  using Clock = std::chrono::steady_clock;
  for (int round = 0; round < 8; ++round) {
    std::atomic<int> asked{0};
    bool cancelled = false, ran_out = false;
    try {
      CancelScope scope([&] { return ++asked >= 3; }, std::chrono::milliseconds(0));
      detail::parallel_for(1, 2, [&](std::size_t) {
        const auto end = Clock::now() + std::chrono::seconds(60);  // a hang, not a latency bound
        while (Clock::now() < end) {
          detail::cancellation_point();
          std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
        ran_out = true;
      });
    } catch (const Cancelled&) {
      cancelled = true;
    }
    test::that("a lone iteration is cancelled, round " + std::to_string(round),
               cancelled && !ran_out);
  }
}

// A pass over the blocks of one large grid (a plain OpenMP region) asks the scope between blocks and
// raises after the region: Cancelled, or the exception of should_stop.
void a_transform_pass_is_cancelled_between_blocks() {
  const std::size_t n = 512;
  ComplexBuffer data(n * n, Complex{1.0, 0.0});
  std::atomic<int> asked{0};
  bool cancelled = false;
  try {
    CancelScope scope([&] { return ++asked >= 3; }, std::chrono::milliseconds(0));
    // 1 ms per row, half a second per pass: the calling thread takes blocks even on a loaded machine
    auto slow = [](std::size_t, Complex*) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    };
    detail::row_pass(data.data(), n, n, FftDirection::forward, 2, slow,
                     [](std::size_t, Complex*) {});
  } catch (const Cancelled&) {
    cancelled = true;
  }
  test::that("a row pass stops once should_stop says so", cancelled && asked.load() >= 3);
  // Rows after the request are skipped: a transformed row of ones is (n, 0, 0, ...), an untouched one is not.
  std::size_t untouched = 0;
  for (std::size_t r = 0; r < n; ++r) untouched += data[r * n] == Complex{1.0, 0.0};
  test::that("the rows after the request are left alone", untouched > 0);

  struct Stop {};
  bool rethrown = false;
  try {
    CancelScope scope([]() -> bool { throw Stop{}; }, std::chrono::milliseconds(0));
    detail::column_pass(data.data(), n, n, 2, [](std::size_t, std::size_t, Complex*) {
      std::this_thread::sleep_for(std::chrono::milliseconds(8));
    });
  } catch (const Stop&) {
    rethrown = true;
  }
  test::that("an exception of should_stop leaves a column pass after its region", rethrown);
}

void threads_are_bounded() {
  LidarSystem s;
  test::throws(
      "threads above max_threads",
      [&] { overlap_rt(s, {100.0}, RtOptions{1e-4, max_threads() + 1, 4000}); }, "threads");
  test::throws(
      "negative threads", [&] { overlap_rt(s, {100.0}, RtOptions{1e-4, -1, 4000}); }, "threads");
  test::that("max_threads at least 256", max_threads() >= 256);
}

void memory_budget() {
  const std::size_t before = max_memory();
  set_max_memory(std::size_t{1} << 20);  // 1 MiB: a 512^2 complex field (4 MiB) no longer fits
  test::throws(
      "Field::gaussian beyond the budget", [] { Field::gaussian(355e-9, 1e-3, 512, 1e-5); },
      "n = 512");
  LidarSystem s;
  test::throws(
      "beam_grid beyond the budget", [&] { overlap_fo(s, {100.0}, FoOptions{512, 10.0, 4096, 1}); },
      "beam_grid");
  set_max_memory(0);
  test::that("0 restores the default", max_memory() == before);
  test::throws(
      "grid side beyond kMaxGridSide",
      [] { Field::gaussian(355e-9, 1e-3, kMaxGridSide + 2, 1e-5); }, "n = ");
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
  test::throws(
      "waist below lambda / pi", [&] { beam(355e-9, 1e-7).validate(); }, "beam.waist_radius");
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
  test::that("round-off within the slack clipped into [0, 1]",
             g[0] == 0.0 && g[1] == 0.5 && g[2] == 1.0);
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
  test::that("saturate: NaN and huge values do not wrap",
             checks::saturate(NAN) == (std::size_t{1} << 62) &&
                 checks::saturate(1e300) == (std::size_t{1} << 62) && checks::saturate(-5.0) == 0 &&
                 checks::saturate(7.9) == 7);
}

}  // namespace

int main() {
  error_inside_the_loop_reaches_the_caller();
  cancel_scope_stops_a_call();
  a_lone_iteration_on_another_thread_is_cancelled();
  a_transform_pass_is_cancelled_between_blocks();
  threads_are_bounded();
  memory_budget();
  physical_scales();
  overlap_values_are_checked();
  return test::report("test_limits");
}
