#include "fourier/scaled_dft.hpp"

#include <cmath>
#include <stdexcept>

#include "core/cancel_every.hpp"
#include "core/constants.hpp"
#include "fourier/zeroed_buffer.hpp"

namespace lidar_overlap {

namespace {

// Work from this size up is split across threads (the transforms' own policy, fft_threads).
constexpr std::size_t kParallelPoints = std::size_t{1} << 20;
int threads_for(std::size_t points) { return points >= kParallelPoints ? fft_threads(points) : 1; }

// exp(i pi alpha k^2) with the phase reduced before the exponential (k^2 alpha can be large).
Complex chirp(double alpha, double k) {
  const double phase = std::remainder(alpha * k * k, 2.0) * kPi;
  return {std::cos(phase), std::sin(phase)};
}

// Each of `rows` rows of length n -> row of length m: out[m'] = sum_n' in[n'] exp(-2 pi i alpha m' n'),
// with centred indices m' = m - M/2, n' = n - N/2. Bluestein: alpha m' n' = alpha/2 (m'^2 + n'^2 - (m'-n')^2).
ComplexBuffer chirp_z_rows(const ComplexBuffer& in, std::size_t rows, std::size_t n, std::size_t m,
                           double alpha) {
  const std::size_t len = next_power_of_two(n + m - 1);
  const double half_n = 0.5 * static_cast<double>(n), half_m = 0.5 * static_cast<double>(m);
  // Kernel exp(+i pi alpha (m' - n')^2) indexed by t = m - n + n - 1.
  ComplexBuffer kernel(len, Complex{});
  for (std::size_t t = 0; t + 1 < n + m; ++t)
    kernel[t] = chirp(alpha, static_cast<double>(t) - (n - 1.0) + half_n - half_m);
  fft_rows(kernel, 1, len, FftDirection::forward);

  // The chirps cost a sine and a cosine per sample: the rows ask for cancellation (detail::RegionStop);
  // the transforms ask for it themselves.
  ComplexBuffer work = detail::zeroed_buffer(rows * len);
  detail::RegionStop in_stop, out_stop;
#pragma omp parallel for num_threads(threads_for(rows* len)) if (rows * len >= kParallelPoints)
  for (long r = 0; r < static_cast<long>(rows); ++r) {
    if (in_stop.stopped()) continue;
    for (std::size_t i = 0; i < n; ++i)
      work[r * len + i] = in[r * n + i] * std::conj(chirp(alpha, static_cast<double>(i) - half_n));
  }
  in_stop.rethrow();
  fft_rows(work, rows, len, FftDirection::forward);
#pragma omp parallel for num_threads(threads_for(rows* len)) if (rows * len >= kParallelPoints)
  for (long r = 0; r < static_cast<long>(rows); ++r)
    for (std::size_t i = 0; i < len; ++i) work[r * len + i] *= kernel[i];
  fft_rows(work, rows, len, FftDirection::backward);

  ComplexBuffer out = detail::zeroed_buffer(rows * m);
  const double scale = 1.0 / static_cast<double>(len);
#pragma omp parallel for num_threads(threads_for(rows* len)) if (rows * len >= kParallelPoints)
  for (long r = 0; r < static_cast<long>(rows); ++r) {
    if (out_stop.stopped()) continue;
    for (std::size_t j = 0; j < m; ++j)
      out[r * m + j] = scale * work[r * len + j + n - 1] *
                       std::conj(chirp(alpha, static_cast<double>(j) - half_m));
  }
  out_stop.rethrow();
  return out;
}

ComplexBuffer transpose(const ComplexBuffer& a, std::size_t rows, std::size_t cols) {
  ComplexBuffer t = detail::zeroed_buffer(rows * cols);
#pragma omp parallel for num_threads(threads_for(rows* cols)) if (rows * cols >= kParallelPoints)
  for (long c = 0; c < static_cast<long>(cols); ++c)
    for (std::size_t r = 0; r < rows; ++r) t[c * rows + r] = a[r * cols + c];
  return t;
}

}  // namespace

ComplexBuffer scaled_dft2d(const ComplexBuffer& in, std::size_t n, std::size_t m, double alpha) {
  if (n % 2 || m % 2 || in.size() != n * n)
    throw std::invalid_argument("scaled_dft2d: n, m even, in n x n");
  const ComplexBuffer along_x = chirp_z_rows(in, n, n, m, alpha);  // n rows (y) x m (x)
  const ComplexBuffer along_y =
      chirp_z_rows(transpose(along_x, n, m), m, n, m, alpha);  // m (x) x m (y)
  return transpose(along_y, m, m);
}

}  // namespace lidar_overlap
