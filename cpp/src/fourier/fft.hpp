// Deterministic FFTs: every transform is made of 1-D FFTW plans over fixed blocks of kFftBlock rows
// and over single columns (gathered by blocks into a contiguous scratch block, fft_passes.hpp),
// planned from the wisdom shipped with the source (fourier/fft_wisdom.hpp: plans FFTW_MEASURE chose
// once), else with FFTW_ESTIMATE on forgotten wisdom. The arithmetic of each row and column then
// depends on the shape alone, never on the thread count, the schedule or timings, so results are
// the same bits for any number of threads and in every process, while the blocks are shared over
// the threads of a team (core/team.hpp). Plans are made once per shape behind one mutex and
// executed on the caller's buffers (FFTW's thread-safe new-array interface). Internal header, not
// installed.
#pragma once

#include <algorithm>
#include <cstddef>
#include <mutex>

#include "lidar_overlap/fourier/complex_buffer.hpp"

namespace lidar_overlap {

enum class FftDirection {
  forward,
  backward
};  // exp(-2 pi i ...) and exp(+2 pi i ...), unnormalised

// Kept for callers that state how hard to plan: both now give the same deterministic plans (1-D
// plans over blocks, from the shipped wisdom), which measure within the time of a measured FFTW 2-D
// plan (docs/fo_propagation.md).
enum class FftPlanning { measure, estimate };

// Rows (or columns) per block: one 1-D plan transforms kFftBlock of them; 8 x 16 bytes fill two
// cache lines per row of a gathered column block.
inline constexpr std::size_t kFftBlock = 8;

// In-place 2-D transform of an n x n row-major array.
void fft2d(ComplexBuffer& data, std::size_t n, FftDirection direction,
           FftPlanning planning = FftPlanning::measure);

// In-place 1-D transforms of `rows` contiguous rows of `length` each.
void fft_rows(ComplexBuffer& data, std::size_t rows, std::size_t length, FftDirection direction);

// 1-D transforms of up to kFftBlock contiguous rows of `length`, in place, on the calling thread.
// The plans come from the process-wide cache on construction; calls are thread-safe. A block of
// `count` rows always uses the same plan, so a row's bits depend only on (length, count).
class RowTransform {
 public:
  RowTransform(std::size_t length, FftDirection direction);
  void operator()(Complex* rows, std::size_t count) const;
  // The `count` columns of a block gathered by detail::column_pass (column c at block + c *
  // stride).
  void columns(Complex* block, std::size_t count, std::size_t stride) const;
  std::size_t length() const { return length_; }

 private:
  std::size_t length_;
  void* block_;   // fftw_plan of kFftBlock rows
  void* single_;  // fftw_plan of one row (the rest of a shape that kFftBlock does not divide)
};

// The same out of place: up to kFftBlock rows of `length`, `distance` apart (a row block, or a
// column block gathered by detail::column_pass), from `in` to `out` (no overlap), on the calling
// thread. FFTW's in-place plans copy through a buffer; these do not (~30 % faster per row at 256).
// A row's bits depend only on (length, count, distance).
class BlockTransform {
 public:
  BlockTransform(std::size_t length, FftDirection direction, std::size_t distance);
  void operator()(const Complex* in, Complex* out, std::size_t count) const;

 private:
  std::size_t length_, distance_;
  void* block_;   // fftw_plan of kFftBlock rows
  void* single_;  // fftw_plan of one row
};

// Whether `p` has the alignment FFTW planned the library's transforms for (any ComplexBuffer has
// it; memory from elsewhere, a NumPy array, usually does).
bool fftw_aligned(const Complex* p);

// The lock around every FFTW planner call in the process (FFTW's planner is not thread-safe).
std::mutex& fftw_planner_mutex();

// Threads for one transform of `points` points: one inside the library's loops over ranges or
// realisations (any OpenMP region), and for transforms too small to share; else
// omp_get_max_threads(), on a busy machine too (detail::all_cores_even_if_busy: the passes' team
// never waits for a late thread).
int fft_threads(std::size_t points);

// Smallest power of two >= v: the sizes FFTW transforms fastest (2^63 for any v beyond it).
inline std::size_t next_power_of_two(std::size_t v) {
  std::size_t p = 1;
  while (p < v && p < (std::size_t{1} << 63)) p <<= 1;
  return p;
}

// Smallest n' >= n of the form 2^a 3^b 5^c 7^d: sizes FFTW also transforms fast, closer to n than a
// power of two (for one-off transforms, where a power of two would only add work). Sizes beyond
// 2^32, which no grid budget allows, are returned as they are (callers check them).
inline std::size_t fast_fft_size(std::size_t n) {
  if (n > (std::size_t{1} << 32)) return n;
  for (std::size_t m = std::max<std::size_t>(n, 2);; ++m) {
    std::size_t r = m;
    for (std::size_t p : {2, 3, 5, 7})
      while (r % p == 0) r /= p;
    if (r == 1) return m;
  }
}

}  // namespace lidar_overlap
