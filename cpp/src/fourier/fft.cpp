#include "fourier/fft.hpp"

#include <fftw3.h>
#include <omp.h>

#include <map>
#include <mutex>
#include <stdexcept>
#include <tuple>

#include "core/parallel.hpp"

namespace lidar_overlap {

namespace {

std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}


// (rows, length, sign, threads, FFTW planner flag) -> plan. Plans live for the whole process.
using PlanKey = std::tuple<std::size_t, std::size_t, int, int, unsigned>;

// Below this many points a transform is too small to gain from threads, and inside a parallel region
// (several transforms at once) threads would only oversubscribe the cores.
constexpr std::size_t kThreadedPoints = std::size_t{1} << 20;

// Inside the library's loops over ranges or realisations (any OpenMP region, even a team of one) every
// transform is single-threaded and planned with FFTW_ESTIMATE, whose choice is fixed for a machine: the
// overlap paths then give the same bits whatever the thread count and in every process. FFTW_MEASURE,
// which times candidates, serves the calls made outside such loops (propagate, point_image).
bool in_library_loop() { return omp_get_level() > 0; }

int threads_for(std::size_t points) {
  if (points < kThreadedPoints || in_library_loop()) return 1;
  return omp_get_max_threads();
}

// FFTW_MEASURE plans a 2048^2 transform for tens of seconds: beyond 1024^2 points it would cost more than it saves.
constexpr std::size_t kMeasuredPoints = std::size_t{1} << 20;

unsigned planner_flag(FftPlanning planning, std::size_t points) {
  const bool measure = planning == FftPlanning::measure && !in_library_loop() && points <= kMeasuredPoints;
  return measure ? FFTW_MEASURE : FFTW_ESTIMATE;
}

fftw_plan get_plan(const PlanKey& key, bool two_d) {
  // Plans live as long as the process: the cache is never destroyed, so no plan outlives FFTW's cleanup
  // and leak checkers see reachable memory.
  static auto& plans = *new std::map<std::pair<bool, PlanKey>, fftw_plan>;
  std::lock_guard<std::mutex> lock(planner_mutex());
  auto it = plans.find({two_d, key});
  if (it != plans.end()) return it->second;
  static bool threads_ready = false;
  if (!threads_ready) {
    if (fftw_init_threads() == 0) throw std::runtime_error("FFTW threads could not be initialised");
    threads_ready = true;
  }
  const auto [rows, length, sign, threads, flag] = key;
  fftw_plan_with_nthreads(threads);
  // FFTW_ESTIMATE would reuse wisdom that FFTW_MEASURE gathered (timings, different in every process) for
  // subproblems: forget it, so that estimate plans depend on the shape alone.
  if (flag == FFTW_ESTIMATE) fftw_forget_wisdom();
  // Plan on a scratch buffer (FFTW_MEASURE overwrites it); execution uses the caller's buffers.
  ComplexBuffer scratch(rows * length);
  auto* p = reinterpret_cast<fftw_complex*>(scratch.data());
  fftw_plan plan;
  if (two_d) {
    plan = fftw_plan_dft_2d(static_cast<int>(rows), static_cast<int>(length), p, p, sign, flag);
  } else {
    const int n = static_cast<int>(length);
    plan = fftw_plan_many_dft(1, &n, static_cast<int>(rows), p, nullptr, 1, n, p, nullptr, 1, n, sign, flag);
  }
  if (!plan) throw std::runtime_error("FFTW could not make a plan");
  plans[{two_d, key}] = plan;
  return plan;
}

int sign_of(FftDirection d) { return d == FftDirection::forward ? FFTW_FORWARD : FFTW_BACKWARD; }

}  // namespace

void fft2d(ComplexBuffer& data, std::size_t n, FftDirection direction, FftPlanning planning) {
  detail::cancellation_point();  // transforms are where long FO runs spend their time
  if (data.size() != n * n) throw std::invalid_argument("fft2d: buffer size is not n * n");
  auto* p = reinterpret_cast<fftw_complex*>(data.data());
  fftw_execute_dft(get_plan({n, n, sign_of(direction), threads_for(n * n), planner_flag(planning, n * n)}, true), p, p);
}

void fft_rows(ComplexBuffer& data, std::size_t rows, std::size_t length, FftDirection direction) {
  detail::cancellation_point();
  if (data.size() != rows * length) throw std::invalid_argument("fft_rows: buffer size is not rows * length");
  auto* p = reinterpret_cast<fftw_complex*>(data.data());
  fftw_execute_dft(get_plan({rows, length, sign_of(direction), threads_for(rows * length),
                            planner_flag(FftPlanning::measure, rows * length)}, false), p, p);
}

}  // namespace lidar_overlap
