#include "fourier/fft_wisdom.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>

#include "fourier/fft.hpp"
#include "fourier/fft_passes.hpp"

namespace lidar_overlap::detail {

namespace {

// kShippedWisdomFftw and kShippedWisdom, written by scripts/make_fft_wisdom.py.
#include "fourier/fft_wisdom.inc"

// The wisdom FFTW holds now, as text; all of it is forgotten after. The caller holds fftw_planner_mutex().
std::string export_and_forget_wisdom() {
  const std::unique_ptr<char, void (*)(void*)> text(fftw_export_wisdom_to_string(), fftw_free);
  fftw_forget_wisdom();
  if (!text) throw std::runtime_error("FFTW could not export its wisdom");
  return text.get();
}

}  // namespace

std::vector<BlockProblem> block_problems(std::size_t length) {
  std::vector<BlockProblem> problems;
  for (const std::size_t count : {kFftBlock, std::size_t{1}})
    for (const int sign : {FFTW_FORWARD, FFTW_BACKWARD})
      for (const bool out_of_place : {false, true})
        problems.push_back({length, count, sign, length, out_of_place});
  return problems;
}

void init_fftw_threads() {
  static bool ready = false;
  if (ready) return;
  if (fftw_init_threads() == 0) throw std::runtime_error("FFTW threads could not be initialised");
  ready = true;
}

fftw_plan plan_block(const BlockProblem& p, unsigned flags) {
  ComplexBuffer scratch(p.distance * p.count * (p.out_of_place ? 2 : 1));
  auto* in = reinterpret_cast<fftw_complex*>(scratch.data());
  auto* out = p.out_of_place ? in + p.distance * p.count : in;
  const int n = static_cast<int>(p.length), distance = static_cast<int>(p.distance);
  fftw_plan_with_nthreads(1);
  return fftw_plan_many_dft(1, &n, static_cast<int>(p.count), in, nullptr, 1, distance, out,
                            nullptr, 1, distance, p.sign, flags);
}

fftw_plan plan_from_wisdom(const BlockProblem& problem, const char* wisdom) {
  init_fftw_threads();
  fftw_forget_wisdom();
  fftw_plan plan = nullptr;
  if (fftw_import_wisdom_from_string(wisdom) != 0)
    plan = plan_block(problem, FFTW_MEASURE | FFTW_WISDOM_ONLY);
  fftw_forget_wisdom();
  return plan;
}

fftw_plan plan_from_wisdom_or_estimate(const BlockProblem& problem, const char* wisdom) {
  fftw_plan plan = plan_from_wisdom(problem, wisdom);
  if (!plan) {
    plan = plan_block(problem, FFTW_ESTIMATE);  // on the wisdom plan_from_wisdom forgot
    fftw_forget_wisdom();
  }
  if (!plan) throw std::runtime_error("FFTW could not make a plan");
  return plan;
}

const char* shipped_fft_wisdom() { return kShippedWisdom; }

const char* shipped_fft_wisdom_fftw() { return kShippedWisdomFftw; }

double block_transform_seconds(std::size_t n, const char* wisdom, int repeats) {
  if (n < kColumnBlock || n % kColumnBlock != 0 || n > 4096)
    throw std::invalid_argument("n = " + std::to_string(n) +
                                " is invalid: expected a multiple of 16 from 16 to 4096");
  if (repeats < 1 || repeats > 10000)
    throw std::invalid_argument("repeats = " + std::to_string(repeats) +
                                " is invalid: expected 1 to 10000");
  // Forward plans [in place, out of place] for 8 rows and for one.
  fftw_plan block[2], single[2];
  {
    std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    for (const BlockProblem& p : block_problems(n)) {
      if (p.sign == FFTW_FORWARD)
        (p.count == 1 ? single : block)[p.out_of_place ? 1 : 0] =
            plan_from_wisdom_or_estimate(p, wisdom);
    }
  }
  const auto run = [](fftw_plan plan, Complex* in, Complex* out) {
    fftw_execute_dft(plan, reinterpret_cast<fftw_complex*>(in),
                     reinterpret_cast<fftw_complex*>(out));
  };
  const std::size_t stride = column_stride(n);
  ComplexBuffer data(n * n, Complex(1.0, 0.5)), out(n * n);
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    // In place (fft2d): rows, then the gathered columns.
    for (std::size_t row = 0; row < n; row += kFftBlock)
      run(block[0], &data[row * n], &data[row * n]);
    column_pass(data.data(), n, n, 1, [&](std::size_t, std::size_t count, Complex* columns) {
      for (std::size_t k = 0; k < count; ++k)
        run(single[0], columns + k * stride, columns + k * stride);
    });
    // Out of place (propagate, the split steps): each gathered column through a buffer.
    for (std::size_t row = 0; row < n; row += kFftBlock)
      run(block[1], &data[row * n], &out[row * n]);
    column_pass(out.data(), n, n, 1, [&](std::size_t, std::size_t count, Complex* columns) {
      Complex* buffer = column_buffer(n);
      for (std::size_t k = 0; k < count; ++k) {
        run(single[1], columns + k * stride, buffer);
        std::copy(buffer, buffer + n, columns + k * stride);
      }
    });
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    for (Complex& v : data) v = Complex(1.0, 0.5);  // bounded values for the next round
  }
  std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  for (fftw_plan p : {block[0], block[1], single[0], single[1]}) fftw_destroy_plan(p);
  return best;
}

std::string measure_fft_wisdom(const std::vector<std::size_t>& lengths) {
  for (const std::size_t length : lengths)
    if (length < 2 || length > (std::size_t{1} << 16))
      throw std::invalid_argument("length = " + std::to_string(length) +
                                  " is invalid: expected 2 to 65536");
  std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  init_fftw_threads();
  fftw_forget_wisdom();
  for (const std::size_t length : lengths) {
    for (const BlockProblem& p : block_problems(length)) {
      const fftw_plan plan = plan_block(p, FFTW_MEASURE);
      if (!plan) throw std::runtime_error("FFTW could not make a plan");
      fftw_destroy_plan(plan);  // its wisdom stays
    }
  }
  return export_and_forget_wisdom();
}

std::string merge_fft_wisdom(const std::vector<std::string>& texts) {
  std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  init_fftw_threads();
  fftw_forget_wisdom();
  for (const std::string& text : texts)
    if (fftw_import_wisdom_from_string(text.c_str()) == 0) {
      fftw_forget_wisdom();
      throw std::invalid_argument("wisdom = '" + text.substr(0, 40) +
                                  "...' is invalid: expected wisdom this FFTW exported");
    }
  return export_and_forget_wisdom();
}

}  // namespace lidar_overlap::detail
