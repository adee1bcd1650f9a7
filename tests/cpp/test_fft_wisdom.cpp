// The block plans made from wisdom (cpp/src/fourier/fft_wisdom.cpp): wisdom measured here imports back
// and gives a plan for every block problem, each plan is the DFT (against a direct sum), wisdom that does
// not fit this FFTW gives no plan (the transforms then use estimated plans) and leaves no wisdom behind,
// and the shipped wisdom gives every plan it was measured for on the FFTW it was measured with.
#include <cmath>
#include <complex>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

#include "check.hpp"
#include "fft_values.hpp"
#include "fourier/fft.hpp"
#include "fourier/fft_wisdom.hpp"

using namespace lidar_overlap;
using detail::BlockProblem;

namespace {

using test::kRoundOff;

std::string exported_wisdom() {
  const std::unique_ptr<char, void (*)(void*)> text(fftw_export_wisdom_to_string(), fftw_free);
  return text ? std::string(text.get()) : std::string("(none)");
}

// plan_from_wisdom under the planner's lock, as the library calls it.
fftw_plan plan_from(const BlockProblem& p, const std::string& wisdom) {
  std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  return detail::plan_from_wisdom(p, wisdom.c_str());
}

// Largest |plan(u) - direct sum| over the problem's rows, relative to the largest value, for a
// pseudo-random u.
double error_against_direct_sum(const BlockProblem& p, fftw_plan plan) {
  const std::size_t size = p.distance * p.count;
  ComplexBuffer in = test::pseudo_random(size), out(size);
  const ComplexBuffer original = in;
  Complex* target = p.out_of_place ? out.data() : in.data();
  fftw_execute_dft(plan, reinterpret_cast<fftw_complex*>(in.data()),
                   reinterpret_cast<fftw_complex*>(target));
  double worst = 0.0;
  for (std::size_t r = 0; r < p.count; ++r)
    for (std::size_t k = 0; k < p.length; ++k)
      worst = std::max(worst,
                       std::abs(test::direct_dft(&original[r * p.distance], p.length, k, p.sign) -
                                target[r * p.distance + k]) /
                           double(p.length));
  return worst;
}

}  // namespace

int main() {
  // Wisdom measured now imports back: every problem of the length gets a plan, and each is the DFT.
  const std::string measured = detail::measure_fft_wisdom({64, 512});
  std::string empty;
  {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    fftw_forget_wisdom();
    empty = exported_wisdom();
  }
  for (const std::size_t length : {64, 512})
    for (const BlockProblem& p : detail::block_problems(length)) {
      const std::string at = " (length " + std::to_string(length) + ", " + std::to_string(p.count) +
                             " rows, sign " + std::to_string(p.sign) +
                             (p.out_of_place ? ", out of place)" : ", in place)");
      const fftw_plan plan = plan_from(p, measured);
      test::that("measured wisdom gives a plan" + at, plan != nullptr);
      if (!plan) continue;
      test::near("plan from wisdom = direct sum" + at, error_against_direct_sum(p, plan), 0.0,
                 kRoundOff);
      fftw_destroy_plan(plan);
    }
  test::that("plan_from_wisdom leaves no wisdom behind", exported_wisdom() == empty);

  // Wisdom that does not fit this FFTW, or holds no plan for the problem, gives none.
  const BlockProblem p512 = detail::block_problems(512).front();
  const std::string version = measured.substr(0, measured.find(' '));
  std::string other_version = measured, other_solver = measured;
  other_version.replace(0, version.size(), "(fftw-0.0.1");
  for (std::size_t at = other_solver.find("fftw_codelet_"); at != std::string::npos;
       at = other_solver.find("fftw_codelet_", at + 1))
    other_solver.replace(at, 13, "fftw_missing_");
  for (const auto& [what, text] : {std::pair<std::string, std::string>{"empty", ""},
                                   {"truncated", measured.substr(0, measured.size() / 2)},
                                   {"of another FFTW version", other_version},
                                   {"naming solvers this FFTW lacks", other_solver},
                                   {"not wisdom", "(not wisdom)"}})
    test::that("wisdom " + what + " gives no plan", plan_from(p512, text) == nullptr);
  BlockProblem unmeasured = p512;
  unmeasured.length = 768;
  unmeasured.distance = 768;
  test::that("wisdom without the problem gives no plan",
             plan_from(unmeasured, measured) == nullptr);
  test::that("refused wisdom leaves no wisdom behind", exported_wisdom() == empty);

  // Merged wisdom plans what each part planned; the timing the wisdom script chooses by runs.
  const std::string merged = detail::merge_fft_wisdom({detail::measure_fft_wisdom({32}), measured});
  test::that("merged wisdom gives the plans of each part",
             plan_from(detail::block_problems(32).back(), merged) != nullptr &&
                 plan_from(p512, merged) != nullptr);
  const double seconds = detail::block_transform_seconds(64, measured.c_str(), 2);
  test::that("block_transform_seconds is a time", std::isfinite(seconds) && seconds > 0.0);
  test::throws(
      "merge_fft_wisdom refuses text that is not wisdom",
      [] { detail::merge_fft_wisdom({"(not wisdom)"}); }, "wisdom");
  test::throws(
      "block_transform_seconds refuses n = 12", [] { detail::block_transform_seconds(12, "", 1); },
      "n = 12");
  test::throws(
      "block_transform_seconds refuses 0 repeats",
      [] { detail::block_transform_seconds(64, "", 0); }, "repeats");
  test::throws(
      "measure_fft_wisdom refuses length 1", [] { detail::measure_fft_wisdom({1}); }, "length");
  test::throws(
      "measure_fft_wisdom refuses length 2^17",
      [] { detail::measure_fft_wisdom({std::size_t{1} << 17}); }, "length");

  // The shipped wisdom, on the FFTW it was measured with, gives plans for some of the powers of two from
  // 16 to 4096 points (those where measured plans were faster than estimated ones), and for each length
  // either all of its problems or none.
  const std::string here = fftw_version, shipped_on = detail::shipped_fft_wisdom_fftw();
  if (here == shipped_on) {
    std::size_t lengths = 0;
    for (std::size_t length = 16; length <= 4096; length *= 2) {
      std::size_t planned = 0;
      const auto problems = detail::block_problems(length);
      for (const BlockProblem& p : problems) {
        const fftw_plan plan = plan_from(p, detail::shipped_fft_wisdom());
        if (plan) {
          ++planned;
          std::lock_guard<std::mutex> lock(fftw_planner_mutex());
          fftw_destroy_plan(plan);
        }
      }
      test::that("shipped wisdom: all or none of the plans of length " + std::to_string(length) +
                     " (" + std::to_string(planned) + " of " + std::to_string(problems.size()) +
                     ")",
                 planned == 0 || planned == problems.size());
      lengths += planned == problems.size();
    }
    test::that("shipped wisdom gives the plans of at least one length", lengths > 0);
  } else {
    std::cout << "test_fft_wisdom: shipped wisdom not checked: measured with " << shipped_on
              << ", this is " << here << " (its transforms use estimated plans)\n";
  }
  return test::report("test_fft_wisdom");
}
