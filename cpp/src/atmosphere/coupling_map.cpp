#include "atmosphere/coupling_map.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/checks.hpp"
#include "core/parallel.hpp"
#include "fourier/fft_passes.hpp"
#include "fourier/overlap_fo_detail.hpp"
#include "fourier/transfer_table.hpp"

namespace lidar_overlap::detail {

CouplingMap::CouplingMap(const LidarSystem& system, const FoReceiver& rx, double z, double dx,
                         std::size_t n, std::size_t np)
    : n_(n), map_(n * n) {
  if (np == 0) return;  // no light reaches the detector plane (spectrum_grid): a zero map, G = 0
  const double to_image = rx.detector_distance() / z, df = 1.0 / (np * dx);
  // T = OTF x disc^ up to the cutoff or the grid's corner frequency (fourier/transfer_table.hpp).
  const double q_max = std::min(rx.cutoff(), df * (0.5 * np * std::sqrt(2.0) + 1.0) / to_image);
  const detail::TransferTable transfer(system, rx, q_max);
  // P: the shift to the detector centre's image and (-1)^(kx+ky), the padded grid's origin at np/2.
  const detail::ShiftPhases phase(
      np, df, system.beam.center(z) + (1.0 / to_image) * system.detector.offset);
  const std::size_t off = np / 2 - n / 2, half = np / 2;
  const std::size_t k_max =
      std::min(half, checks::saturate(q_max * to_image / df));  // beyond: T = 0
  const std::size_t rows = k_max + 1;
  const RowTransform backward(np, FftDirection::backward);
  ComplexBuffer block(kFftBlock * np);
  // T(|kx|, |ky|) on the quarter grid kx = 0 .. np/2, ky < rows, row by row; q grows along a row, so a row
  // ends at q_max. Up to kMapTable values are tabled first, each evaluated once by T(kx, ky) = T(ky, kx).
  const std::size_t width = half + 1;
  const bool tabled = static_cast<double>(rows) * static_cast<double>(width) <= kMapTable;
  std::vector<double> t(tabled ? rows * width : 0, 0.0), own(tabled ? 0 : 2 * width);
  auto evaluate = [&](std::size_t ky, std::size_t from, double* row, bool mirror) {
    const double fy = df * static_cast<double>(ky);
    for (std::size_t a = from; a <= half; ++a) {
      const double fx = df * static_cast<double>(a), q = std::sqrt(fx * fx + fy * fy) / to_image;
      if (!(q < q_max)) break;
      row[a] = transfer(q);
      if (mirror && a < rows) t[a * width + ky] = row[a];
    }
  };
  for (std::size_t ky = 0; tabled && ky < rows; ++ky) {
    if (ky % 64 == 0) detail::cancellation_point();  // up to kMapTable / 2 evaluations of T
    evaluate(ky, ky, &t[ky * width], true);
  }
  auto t_row = [&](std::size_t ky, std::size_t slot) -> const double* {
    if (tabled) return &t[ky * width];
    double* row = &own[slot * width];
    std::fill(row, row + width, 0.0);
    if (ky < rows) evaluate(ky, 0, row, false);
    return row;
  };
  // Along x: r[ix * rows + ky] = R(ky, off + ix), two rows ky per transform, kFftBlock transforms a block;
  // T(np/2, ky) kept for the Nyquist column.
  std::vector<double> r(n * rows), nyquist(rows), zeros(width, 0.0);
  for (std::size_t k0 = 0; k0 < rows; k0 += 2 * kFftBlock) {
    detail::cancellation_point();  // 2 kFftBlock rows of np
    const std::size_t count = std::min(kFftBlock, (rows - k0 + 1) / 2);
    for (std::size_t b = 0; b < count; ++b) {
      const std::size_t ky = k0 + 2 * b;
      const double* t_even = t_row(ky, 0);
      const double* t_odd = ky + 1 < rows ? t_row(ky + 1, 1) : zeros.data();
      nyquist[ky] = t_even[half];
      if (ky + 1 < rows) nyquist[ky + 1] = t_odd[half];
      Complex* row = &block[b * np];
      for (std::size_t kx = 0; kx < np; ++kx) {
        const std::size_t a = kx <= half ? kx : np - kx;
        row[kx] = detail::product(Complex(t_even[a], t_odd[a]), phase.x[kx]);
      }
      row[half] = Complex{};  // the Nyquist column: separately, below
    }
    backward(block.data(), count);
    // Written by window column, the block's 2 count rows side by side: r is laid out by column, and row by
    // row every write would land on another cache line.
    for (std::size_t ix = 0; ix < n; ++ix) {
      double* out = &r[ix * rows + k0];
      for (std::size_t b = 0; b < count; ++b) {
        const Complex v = block[b * np + off + ix];
        out[2 * b] = v.real();
        if (k0 + 2 * b + 1 < rows) out[2 * b + 1] = v.imag();
      }
    }
  }
  // Along y: two window columns per transform.
  const double scale = df * df / (to_image * to_image * rx.aperture_area());
  const double nyquist_y = phase.y[half].real();  // Re Py(np/2): all of row np/2 that reaches Re m
  for (std::size_t c0 = 0; c0 < n; c0 += 2 * kFftBlock) {
    detail::cancellation_point();
    const std::size_t count = std::min(kFftBlock, (n - c0) / 2);  // n is even
    std::fill(block.begin(), block.begin() + count * np, Complex{});
    for (std::size_t b = 0; b < count; ++b) {
      const double* ra = &r[(c0 + 2 * b) * rows];
      const double* rb = ra + rows;
      Complex* column = &block[b * np];
      column[0] = Complex(ra[0], rb[0]) * phase.y[0].real();  // Py(0) = 1
      for (std::size_t ky = 1; ky < rows; ++ky) {
        if (ky == half) {
          column[half] = Complex(ra[ky], rb[ky]) * nyquist_y;
          continue;
        }
        column[ky] = Complex(ra[ky] * phase.y[ky].real() - rb[ky] * phase.y[ky].imag(),
                             ra[ky] * phase.y[ky].imag() + rb[ky] * phase.y[ky].real());
        const Complex& p = phase.y[np - ky];
        column[np - ky] =
            Complex(ra[ky] * p.real() - rb[ky] * p.imag(), ra[ky] * p.imag() + rb[ky] * p.real());
      }
    }
    backward(block.data(), count);
    for (std::size_t b = 0; b < count; ++b) {
      const Complex* column = &block[b * np + off];
      for (std::size_t iy = 0; iy < n; ++iy) {
        map_[(c0 + 2 * b) * n + iy] = column[iy].real() * scale;
        map_[(c0 + 2 * b + 1) * n + iy] = column[iy].imag() * scale;
      }
    }
  }
  // The Nyquist column, if T reaches it.
  if (std::any_of(nyquist.begin(), nyquist.end(), [](double t) { return t != 0.0; })) {
    Complex* s = block.data();
    std::fill(s, s + np, Complex{});
    for (std::size_t ky = 0; ky < rows; ++ky) {
      s[ky] = nyquist[ky] * phase.y[ky];
      if (ky > 0 && ky < half) s[np - ky] = nyquist[ky] * phase.y[np - ky];
    }
    backward(s, 1);
    const Complex px = phase.x[half];
    for (std::size_t ix = 0; ix < n; ++ix) {
      const double sign = (off + ix) % 2 ? -1.0 : 1.0;
      for (std::size_t iy = 0; iy < n; ++iy)
        map_[ix * n + iy] += sign * (px * s[off + iy]).real() * scale;
    }
  }
}

}  // namespace lidar_overlap::detail
