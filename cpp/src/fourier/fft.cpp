#include "fourier/fft.hpp"

#include <fftw3.h>
#include <omp.h>

#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <tuple>

#include "core/parallel.hpp"
#include "fourier/fft_passes.hpp"
#include "fourier/fft_wisdom.hpp"

namespace lidar_overlap {

namespace {

// From this many points a transform is shared over threads: 256^2 takes ~0.3 ms on one core, which
// a dynamically scheduled team still shortens; below it a team's start-up is not repaid.
constexpr std::size_t kThreadedPoints = std::size_t{1} << 16;
// Every threaded transform takes all cores, also while a late team holds `threads = 0` to one
// thread (core/parallel.hpp): its team does not wait for a thread that starts late (core/team.hpp),
// so on a busy machine a second thread helps when the scheduler runs it and costs nothing when it
// does not, whereas one thread among busy processes gets a single share of the cores against every
// other program's full team.

// (length, rows per plan, sign, distance between rows, out of place) -> plan, made once and kept
// for the whole process (the map is never destroyed, so no plan outlives FFTW's cleanup and leak
// checkers see reachable memory).
fftw_plan block_plan(std::size_t length, std::size_t count, int sign, std::size_t distance = 0,
                     bool out_of_place = false) {
  if (distance == 0) distance = length;
  static auto& plans =
      *new std::map<std::tuple<std::size_t, std::size_t, int, std::size_t, bool>, fftw_plan>;
  std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  const auto key = std::make_tuple(length, count, sign, distance, out_of_place);
  if (auto it = plans.find(key); it != plans.end()) return it->second;
  // Plans come from the shipped wisdom (fourier/fft_wisdom.hpp), else FFTW_ESTIMATE on forgotten
  // wisdom: either depends on the shape alone, never on timings gathered in this process by any
  // FFTW user. Plans are single-threaded: threads share blocks instead.
  const fftw_plan plan = detail::plan_from_wisdom_or_estimate(
      {length, count, sign, distance, out_of_place}, detail::shipped_fft_wisdom());
  plans[key] = plan;
  return plan;
}

int sign_of(FftDirection d) { return d == FftDirection::forward ? FFTW_FORWARD : FFTW_BACKWARD; }

// `count` rows `distance` apart from `in` to `out` (the same array for in-place plans): the block
// plan for a whole block, else the single-row plan row by row. Plans were made on FFTW-aligned
// memory; std::complex<double> arrays keep that alignment (16 bytes). Complex out-of-place plans
// preserve their input.
void execute_blocks(void* block, void* single, const Complex* in, Complex* out, std::size_t count,
                    std::size_t distance, const char* who) {
  auto* i = reinterpret_cast<fftw_complex*>(const_cast<Complex*>(in));
  auto* o = reinterpret_cast<fftw_complex*>(out);
  if (fftw_alignment_of(reinterpret_cast<double*>(i)) != 0 ||
      fftw_alignment_of(reinterpret_cast<double*>(o)) != 0)
    throw std::logic_error(std::string(who) +
                           ": a buffer without the alignment of std::complex<double>");
  if (count == kFftBlock) {
    fftw_execute_dft(static_cast<fftw_plan>(block), i, o);
    return;
  }
  for (std::size_t r = 0; r < count; ++r)
    fftw_execute_dft(static_cast<fftw_plan>(single), i + r * distance, o + r * distance);
}

}  // namespace

bool fftw_aligned(const Complex* p) {
  return fftw_alignment_of(reinterpret_cast<double*>(const_cast<Complex*>(p))) == 0;
}

std::mutex& fftw_planner_mutex() {
  static std::mutex m;
  return m;
}

RowTransform::RowTransform(std::size_t length, FftDirection direction)
    : length_(length),
      block_(block_plan(length, kFftBlock, sign_of(direction))),
      single_(block_plan(length, 1, sign_of(direction))) {}

void RowTransform::operator()(Complex* rows, std::size_t count) const {
  execute_blocks(block_, single_, rows, rows, count, length_, "RowTransform");
}

void RowTransform::columns(Complex* block, std::size_t count, std::size_t stride) const {
  for (std::size_t c = 0; c < count; ++c) (*this)(block + c * stride, 1);
}

BlockTransform::BlockTransform(std::size_t length, FftDirection direction, std::size_t distance)
    : length_(length),
      distance_(distance),
      block_(block_plan(length, kFftBlock, sign_of(direction), distance, true)),
      single_(block_plan(length, 1, sign_of(direction), distance, true)) {
  if (distance < length) throw std::logic_error("BlockTransform: rows closer than their length");
}

void BlockTransform::operator()(const Complex* in, Complex* out, std::size_t count) const {
  execute_blocks(block_, single_, in, out, count, distance_, "BlockTransform");
}

int fft_threads(std::size_t points) {
  if (points < kThreadedPoints || omp_get_level() > 0) return 1;
  return detail::all_cores_even_if_busy();
}

void fft2d(ComplexBuffer& data, std::size_t n, FftDirection direction, FftPlanning) {
  detail::cancellation_point();  // transforms are where long FO runs spend their time
  if (data.size() != n * n) throw std::invalid_argument("fft2d: buffer size is not n * n");
  const int threads = fft_threads(n * n);
  detail::row_pass(data.data(), n, n, direction, threads);
  const RowTransform columns(n, direction);
  detail::column_pass(data.data(), n, n, threads,
                      [&](std::size_t, std::size_t count, Complex* block) {
                        columns.columns(block, count, detail::column_stride(n));
                      });
}

void fft_rows(ComplexBuffer& data, std::size_t rows, std::size_t length, FftDirection direction) {
  detail::cancellation_point();
  if (data.size() != rows * length)
    throw std::invalid_argument("fft_rows: buffer size is not rows * length");
  detail::row_pass(data.data(), rows, length, direction, fft_threads(rows * length));
}

}  // namespace lidar_overlap
