// The two passes a 2-D transform is made of, with hooks that run on each row or column block while it is
// in cache, so that the multiplications and sums of a propagation cost no pass of their own (fused).
// Blocks are fixed by the shape and handed out dynamically to a team (core/team.hpp): a thread that the
// machine's load delays holds up one block, not a share of the pass. Hooks must not throw. A pass asks the
// caller's CancelScope before each block (a pass over a 16384^2 grid takes seconds; for_each_block) and
// throws Cancelled after the team has ended, never from inside it. Internal header, not installed.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <utility>

#include "core/parallel.hpp"
#include "core/team.hpp"
#include "fourier/fft.hpp"

namespace lidar_overlap::detail {

// a b, the same bits as std::complex's product for finite values, without its check for a NaN result (a
// branch to __muldc3 per product, which keeps the hooks' loops from vectorising).
inline Complex product(Complex a, Complex b) {
  return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()};
}

// Blocks of `width` lines in `lines` lines (the last one shorter).
inline long block_count(std::size_t lines, std::size_t width = kFftBlock) {
  return static_cast<long>((lines + width - 1) / width);
}

// For each row r of a rows x length row-major array: before(r, row), its 1-D transform, after(r, row).
template <class Before, class After>
void row_pass(Complex* data, std::size_t rows, std::size_t length, FftDirection direction,
              int threads, Before&& before, After&& after) {
  const RowTransform transform(length, direction);
  for_each_block(block_count(rows), threads, [&](long b) {
    const std::size_t r0 = static_cast<std::size_t>(b) * kFftBlock,
                      count = std::min(kFftBlock, rows - r0);
    Complex* block = data + r0 * length;
    for (std::size_t r = 0; r < count; ++r) before(r0 + r, block + r * length);
    transform(block, count);
    for (std::size_t r = 0; r < count; ++r) after(r0 + r, block + r * length);
  });
}

inline void row_pass(Complex* data, std::size_t rows, std::size_t length, FftDirection direction,
                     int threads) {
  auto none = [](std::size_t, Complex*) {};
  row_pass(data, rows, length, direction, threads, none, none);
}

// One complex value as one 16-byte move (a plain assignment copies its two parts one by one).
inline void copy_one(const Complex* from, Complex* to) {
  std::memcpy(static_cast<void*>(to), from, sizeof(Complex));
}

// Columns [0, K) of a rows x cols array (starting at `first`) into K contiguous columns, and back.
template <std::size_t K>
void gather(const Complex* first, std::size_t rows, std::size_t cols, std::size_t stride,
            Complex* block) {
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t c = 0; c < K; ++c) copy_one(first + r * cols + c, block + c * stride + r);
}
template <std::size_t K>
void scatter(const Complex* block, std::size_t rows, std::size_t cols, std::size_t stride,
             Complex* first) {
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t c = 0; c < K; ++c) copy_one(block + c * stride + r, first + r * cols + c);
}

// Columns per gathered block: each column is transformed alone (by the single-row plans), so the width
// changes no bits; 16 values of 16 bytes are four cache lines of each row, read and written at once
// (2 threads: a column pass of 512^2 took 0.93-0.97 ms against 1.05 ms with 8 columns, 1024^2 5.1-5.2
// against 5.5-5.7 ms; 2048^2 the same). The scratch block (263 KB at 1024^2) stays in a core's L2 up
// to 1024^2.
inline constexpr std::size_t kColumnBlock = 16;

// Distance between the gathered columns of a block: one cache line more than the column, so that the
// block's columns (and the rows they come from, a power of two apart) do not share cache sets.
inline std::size_t column_stride(std::size_t rows) { return rows + 4; }

// For each block of up to kColumnBlock columns of a rows x cols row-major array `from`: the columns gathered
// into a scratch block (column c of the block at scratch + c * column_stride(rows), contiguous), work(first
// column, count, scratch), the block written to the same columns of `to` (`from` itself, an array that
// does not overlap it, or null: the work reads the block and nothing is written back). RowTransform::columns
// transforms such a block.
template <class Work>
void column_pass(const Complex* from, Complex* to, std::size_t rows, std::size_t cols, int threads,
                 Work&& work) {
  const std::size_t stride = column_stride(rows);
  for_each_block(block_count(cols, kColumnBlock), threads, [&](long b) {
    thread_local ComplexBuffer
        scratch;  // kept from pass to pass: an allocation per pass is measurable
    if (scratch.size() < kColumnBlock * stride) scratch.resize(kColumnBlock * stride);
    const std::size_t c0 = static_cast<std::size_t>(b) * kColumnBlock,
                      count = std::min(kColumnBlock, cols - c0);
    Complex* s = scratch.data();
    if (count == kColumnBlock) {  // the common case, unrolled by the compiler
      gather<kColumnBlock>(from + c0, rows, cols, stride, s);
      work(c0, count, s);
      if (to) scatter<kColumnBlock>(s, rows, cols, stride, to + c0);
    } else {
      for (std::size_t r = 0; r < rows; ++r)
        for (std::size_t c = 0; c < count; ++c)
          copy_one(from + r * cols + c0 + c, s + c * stride + r);
      work(c0, count, s);
      if (to)
        for (std::size_t r = 0; r < rows; ++r)
          for (std::size_t c = 0; c < count; ++c)
            copy_one(s + c * stride + r, to + r * cols + c0 + c);
    }
  });
}

// A buffer of at least n values for the calling thread, kept from call to call: one column transformed out
// of place inside a column pass's work (BlockTransform with count 1). Not for two uses alive at once.
inline Complex* column_buffer(std::size_t n) {
  thread_local ComplexBuffer column;
  if (column.size() < n) column.resize(n);
  return column.data();
}

// The same in place.
template <class Work>
void column_pass(Complex* data, std::size_t rows, std::size_t cols, int threads, Work&& work) {
  column_pass(static_cast<const Complex*>(data), data, rows, cols, threads,
              std::forward<Work>(work));
}

// Out of place, through a per-thread scratch block (BlockTransform): for each row r of a rows x length
// row-major array, fill(r, scratch_row) writes all `length` values the row's transform starts from (from the
// row itself or from anywhere else), the transform writes row r of `data`, then after(r, row).
template <class Fill, class After>
void row_pass_into(Complex* data, std::size_t rows, std::size_t length, FftDirection direction,
                   int threads, Fill&& fill, After&& after) {
  const BlockTransform transform(length, direction, length);
  for_each_block(block_count(rows), threads, [&](long b) {
    thread_local ComplexBuffer scratch;
    if (scratch.size() < kFftBlock * length) scratch.resize(kFftBlock * length);
    const std::size_t r0 = static_cast<std::size_t>(b) * kFftBlock,
                      count = std::min(kFftBlock, rows - r0);
    for (std::size_t r = 0; r < count; ++r) fill(r0 + r, scratch.data() + r * length);
    Complex* block = data + r0 * length;
    transform(scratch.data(), block, count);
    for (std::size_t r = 0; r < count; ++r) after(r0 + r, block + r * length);
  });
}

// Out of place straight from another array: for each block of rows of a rows x length row-major array `in`,
// read(r, row of in) for each row (sums of the input), then the block's transforms from `in` into the same
// rows of `out` (no overlap; both with FFTW's alignment, fftw_aligned). The same plans, so the same bits, as
// row_pass_into filled with copies of the rows of `in`, without the copies.
template <class Read>
void row_pass_from(const Complex* in, Complex* out, std::size_t rows, std::size_t length,
                   FftDirection direction, int threads, Read&& read) {
  const BlockTransform transform(length, direction, length);
  for_each_block(block_count(rows), threads, [&](long b) {
    const std::size_t r0 = static_cast<std::size_t>(b) * kFftBlock,
                      count = std::min(kFftBlock, rows - r0);
    for (std::size_t r = 0; r < count; ++r) read(r0 + r, in + (r0 + r) * length);
    transform(in + r0 * length, out + r0 * length, count);
  });
}

}  // namespace lidar_overlap::detail
