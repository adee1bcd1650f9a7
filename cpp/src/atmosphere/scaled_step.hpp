// The split step of the turbulent FO path (overlap_turbulent.cpp): the scaled angular-spectrum method, whose
// grid spacing follows the beam's growth, cut at the spectrum so that one forward transform serves every
// plane up to the next phase screen. Internal header, not installed.
#pragma once

#include <complex>
#include <cstring>
#include <vector>

#include "atmosphere/phasor.hpp"
#include "core/constants.hpp"
#include "core/parallel.hpp"
#include "fourier/fft.hpp"
#include "fourier/fft_passes.hpp"
#include "lidar_overlap/fourier/field.hpp"

namespace lidar_overlap::detail {

// One scaled step (J. D. Schmidt, Numerical Simulation of Optical Wave Propagation, 2010, Sec. 8.2) takes
// n x n samples of spacing d1 to spacing d2 = m d1 at a plane dz further: U2 = Q3 IFFT[Q2 FFT(Q1 U1)] / m
// with Q1 = exp(i k (1 - m) r1^2 / (2 dz)), Q2 = exp(-i 2 pi^2 dz f^2 / (m k)), Q3 = exp(i k (m - 1) r2^2 /
// (2 m dz)), all separable in x and y. Between two screens the planes' spacings lie on a cone, m = 1 + c dz
// (segment_plan.hpp): then Q1 = exp(-i k c r1^2 / 2) is the same for every plane of the segment, and one
// Departure (Q1, forward transform) feeds an Arrival (Q2, backward transform) per plane. A chain of steps
// along the same cone is the same operator (its inner Q3 Q1 and FFT IFFT cancel), so nothing is lost.

// Leaving a plane of spacing d: the field times the screen's exp(i phase), the previous arrival's Q3 (left
// until now: a phase does not change the irradiance a range reads) and this segment's Q1, then the forward
// transform (out of place through a row block, then back into the field). The 1 / n^2 of the transform
// pair is applied here.
class Departure {
 public:
  // `incoming`: the arriving step's Q3 curvature, c / m of that step (1/m; 0 at the transmitter);
  // `curvature`: this segment's cone, c (1/m).
  Departure(std::size_t n, double spacing, double incoming, double curvature, double lambda)
      : n_(n), factor_y_(n), factor_x_(n) {
    const double k = 2.0 * kPi / lambda, scale = 1.0 / (double(n) * double(n));
    for (std::size_t i = 0; i < n; ++i) {
      const double x = (static_cast<double>(i) - 0.5 * n) * spacing;
      factor_y_[i] = std::polar(1.0, 0.5 * k * (incoming - curvature) * x * x);
      factor_x_[i] = factor_y_[i] * scale;
    }
  }
  // `source` (n x n, or null: u itself): a field shared by many realisations, read instead of u's values.
  // The screen at this plane (or none): its phases in rad (`screen`, each made exp(i phase) by
  // detail::phasor) or their exp(i phase) made beforehand (`phasor`), n x n.
  void execute(Field& u, const Complex* source, const double* screen, const Complex* phasor) const {
    cancellation_point();
    const std::size_t n = n_;
    Complex* data = u.values.data();
    auto fill = [&](std::size_t iy, Complex* row) {
      const Complex* in = (source ? source : data) + iy * n;
      const Complex a = factor_y_[iy];
      if (screen || phasor) {
        const Complex* p = phasor ? phasor + iy * n : screen_row(screen + iy * n, n);
        for (std::size_t ix = 0; ix < n; ++ix)
          row[ix] = product(product(in[ix], p[ix]), product(a, factor_x_[ix]));
      } else {
        for (std::size_t ix = 0; ix < n; ++ix) row[ix] = product(in[ix], product(a, factor_x_[ix]));
      }
    };
    const int threads = fft_threads(n * n);
    row_pass_into(data, n, n, FftDirection::forward, threads, fill, [](std::size_t, Complex*) {});
    const RowTransform forward(n, FftDirection::forward);
    column_pass(data, n, n, threads, [&](std::size_t, std::size_t count, Complex* block) {
      forward.columns(block, count, column_stride(n));
    });
  }

 private:
  // exp(i phase) of one row of a screen, in the calling thread's buffer.
  static const Complex* screen_row(const double* phase, std::size_t n) {
    thread_local ComplexBuffer row;
    if (row.size() < n) row.resize(n);
    phasors(phase, row.data(), n);
    return row.data();
  }

  std::size_t n_;
  std::vector<Complex> factor_y_, factor_x_;
};

// Reaching a plane dz beyond the departure, at spacing m d (m = 1 + c dz): the spectrum times Q2 and 1 / m,
// then the backward transform. The field reached lacks its Q3, a phase (Departure applies it if the field
// goes on).
class Arrival {
 public:
  Arrival(std::size_t n, double spacing, double dz, double curvature, double lambda)
      : n_(n), m_(1.0 + curvature * dz), q2_y_(n), q2_x_(n) {
    const double k = 2.0 * kPi / lambda;
    for (std::size_t i = 0; i < n; ++i) {
      const double f =
          (i < n / 2 ? static_cast<double>(i) : static_cast<double>(i) - static_cast<double>(n)) /
          (n * spacing);
      q2_y_[i] = std::polar(1.0, -2.0 * kPi * kPi * dz * f * f / (m_ * k));
      q2_x_[i] = q2_y_[i] / m_;
    }
    spacing_ = spacing * m_;
    q3_curvature_ = curvature / m_;
  }
  double spacing() const { return spacing_; }  // m, of the plane reached
  double q3_curvature() const {
    return q3_curvature_;
  }  // c / m (1/m): Q3 = exp(i k (c / m) r2^2 / 2)

  // The field reached, by columns: the rows are transformed first (into `rows`, n x n, which may be the
  // spectrum itself), then each column of the field, contiguous, is handed to read(ix, column) and written
  // back to `field` (the field reached, at its spacing; or null: the columns are only read, one strided
  // pass fewer). `read` may run on several threads at once, for different columns.
  template <class Read>
  void execute(const Field& spectrum, Field& rows, Field* field, Read&& read) const {
    cancellation_point();
    const std::size_t n = n_;
    const int threads = fft_threads(n * n);
    const Complex* in = spectrum.values.data();
    auto q2 = [&](std::size_t iy, Complex* row) {
      const Complex a = q2_y_[iy];
      const Complex* from = in + iy * n;
      for (std::size_t ix = 0; ix < n; ++ix) row[ix] = product(from[ix], product(a, q2_x_[ix]));
    };
    row_pass_into(rows.values.data(), n, n, FftDirection::backward, threads, q2,
                  [](std::size_t, Complex*) {});
    const std::size_t stride = column_stride(n);
    if (field) {
      const RowTransform backward(n, FftDirection::backward);
      column_pass(rows.values.data(), field->values.data(), n, n, threads,
                  [&](std::size_t c0, std::size_t count, Complex* block) {
                    backward.columns(block, count, stride);
                    for (std::size_t c = 0; c < count; ++c)
                      read(c0 + c, static_cast<const Complex*>(block + c * stride));
                  });
      field->spacing = spacing_;
      return;
    }
    // Only read: each column transformed out of place into a buffer of one column, which FFTW's in-place
    // plans would copy through anyway.
    const BlockTransform backward(n, FftDirection::backward, n);
    column_pass(rows.values.data(), nullptr, n, n, threads,
                [&](std::size_t c0, std::size_t count, Complex* block) {
                  Complex* column = column_buffer(n);
                  for (std::size_t c = 0; c < count; ++c) {
                    backward(block + c * stride, column, 1);
                    read(c0 + c, static_cast<const Complex*>(column));
                  }
                });
  }

 private:
  std::size_t n_;
  double m_, spacing_ = 0.0, q3_curvature_ = 0.0;
  std::vector<Complex> q2_y_, q2_x_;
};

// Sums of one column of a field for a range's coupling map (CouplingMap, by columns): sums[2 ix] = sum
// |u|^2, sums[2 ix + 1] = sum |u|^2 map over column ix.
inline void map_column_sums(std::size_t ix, const Complex* column, std::size_t n, const double* map,
                            double* sums) {
  const double* m = map + ix * n;
  // (re^2, im^2) of each sample as one two-lane vector, in two interleaved partial sums (one chain of
  // additions would wait on each one's latency); the lanes and partial sums are added in a fixed order.
  using V = phasor_kernel::Doubles;
  V e[2] = {V{0.0, 0.0}, V{0.0, 0.0}}, em[2] = {V{0.0, 0.0}, V{0.0, 0.0}};
  for (std::size_t iy = 0; iy < n; ++iy) {
    V u;
    std::memcpy(&u, column + iy, sizeof u);
    const V v = u * u;
    e[iy & 1] += v;
    em[iy & 1] += v * m[iy];
  }
  const V et = e[0] + e[1], emt = em[0] + em[1];
  sums[2 * ix] = et[0] + et[1];
  sums[2 * ix + 1] = emt[0] + emt[1];
}

}  // namespace lidar_overlap::detail
