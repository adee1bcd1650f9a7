// The split step of the turbulent FO path (overlap_turbulent.cpp): the scaled angular-spectrum method that
// lets each plane's grid follow the beam's growth.
#pragma once

#include <complex>
#include <vector>

#include "atmosphere/phasor.hpp"
#include "core/constants.hpp"
#include "core/parallel.hpp"
#include "fourier/fft.hpp"
#include "fourier/fft_passes.hpp"
#include "lidar_overlap/fourier/field.hpp"

namespace lidar_overlap::detail {

// One split step of the scaled angular-spectrum (Fresnel transfer function) method: n x n samples of
// spacing d1 at one plane to spacing d2 = m d1 at a plane dz further, with m chosen to follow the beam's
// growth, U2 = Q3 IFFT[Q2 FFT(Q1 U1 / m)] / n^2 with Q1 = exp(i k (1 - m) r1^2 / (2 dz)), Q2 = exp(-i 2
// pi^2 dz f^2 / (m k)), Q3 = exp(i k (m - 1) r2^2 / (2 m dz)) (J. D. Schmidt, Numerical Simulation of
// Optical Wave Propagation, 2010, Sec. 8.2). All three are separable in x and y. A step leaves its Q3 / n^2
// to the next one, which applies it with its own Q1 in one pass (finish() after the last): a phase and a
// constant change neither the phase screens' effect nor the irradiance's shape the overlap reads.
class ScaledStep {
 public:
  ScaledStep(std::size_t n, double d1, double d2, double dz, double lambda, const ScaledStep* before)
      : n_(n), d2_(d2), in_x_(n), in_y_(n), q2_(n), q3_(n) {
    const double k = 2.0 * kPi / lambda, m = d2 / d1;
    for (std::size_t i = 0; i < n; ++i) {
      const double x1 = (static_cast<double>(i) - 0.5 * n) * d1, x2 = (static_cast<double>(i) - 0.5 * n) * d2;
      const double f = (i < n / 2 ? static_cast<double>(i) : static_cast<double>(i) - static_cast<double>(n)) / (n * d1);
      const Complex q1 = std::polar(1.0, k * (1.0 - m) * x1 * x1 / (2.0 * dz));
      in_y_[i] = before ? before->q3_[i] * q1 : q1;
      in_x_[i] = in_y_[i] * (before ? before->scale_out_ / m : 1.0 / m);
      q2_[i] = std::polar(1.0, -2.0 * kPi * kPi * dz * f * f / (m * k));
      q3_[i] = std::polar(1.0, k * (m - 1.0) * x2 * x2 / (2.0 * m * dz));
    }
    scale_out_ = 1.0 / (static_cast<double>(n) * n);
  }
  // One pass per axis and direction, the multiplications fused into them while the rows or columns are in
  // cache: Q1 before the forward row transforms; Q2 between the forward and backward transforms of each
  // column block (the backward 2-D transform runs columns first); then the backward row transforms.
  // `screen` (n x n phases in rad, or null): a phase screen at the plane the step leaves, applied in the
  // pass of Q1 (exp(i screen) first, as apply_phase_screen would, by detail::phasor). `map` (n x n, or null): on return,
  // row_sums[2 iy] and row_sums[2 iy + 1] hold sum |u|^2 and sum |u|^2 map over row iy of the field reached.
  // `phasor` (n x n, or null; with no screen): exp(i screen) made beforehand, for fields that share a screen.
  void execute(Field& u, const double* screen = nullptr, const double* map = nullptr, double* row_sums = nullptr,
               const Complex* phasor_table = nullptr) const {
    cancellation_point();
    const int threads = fft_threads(n_ * n_);
    const std::size_t n = n_;
    Complex* data = u.values.data();
    auto q1 = [&](std::size_t iy, Complex* row) {
      if (screen) {
        const double* phase = screen + iy * n;
        for (std::size_t ix = 0; ix < n; ++ix) row[ix] = product(row[ix], phasor(phase[ix]));
      } else if (phasor_table) {
        const Complex* p = phasor_table + iy * n;
        for (std::size_t ix = 0; ix < n; ++ix) row[ix] = product(row[ix], p[ix]);
      }
      const Complex a = in_y_[iy];
      for (std::size_t ix = 0; ix < n; ++ix) row[ix] = product(row[ix], product(a, in_x_[ix]));
    };
    auto none = [](std::size_t, Complex*) {};
    row_pass(data, n, n, FftDirection::forward, threads, q1, none);
    const RowTransform forward(n, FftDirection::forward), backward(n, FftDirection::backward);
    const std::size_t stride = column_stride(n);
    column_pass(data, n, n, threads, [&](std::size_t c0, std::size_t count, Complex* block) {
      forward.columns(block, count, stride);
      for (std::size_t c = 0; c < count; ++c) {
        Complex* column = block + c * stride;
        const Complex fx = q2_[c0 + c];
        for (std::size_t iy = 0; iy < n; ++iy) column[iy] = product(column[iy], product(q2_[iy], fx));
      }
      backward.columns(block, count, stride);
    });
    auto sums = [&](std::size_t iy, Complex* row) {
      if (!map) return;
      const double* m = map + iy * n;
      double e = 0.0, em = 0.0;
      for (std::size_t ix = 0; ix < n; ++ix) {
        const double v = std::norm(row[ix]);
        e += v;
        em += v * m[ix];
      }
      row_sums[2 * iy] = e;
      row_sums[2 * iy + 1] = em;
    };
    row_pass(data, n, n, FftDirection::backward, threads, none, sums);
    u.spacing = d2_;
  }
  void finish(Field& u) const {
    std::vector<Complex> out_x(q3_);
    for (Complex& c : out_x) c *= scale_out_;
    multiply(u, q3_, out_x);
  }

 private:
  void multiply(Field& u, const std::vector<Complex>& fy, const std::vector<Complex>& fx) const {
    for (std::size_t iy = 0; iy < n_; ++iy) {
      Complex* row = &u.values[iy * n_];
      const Complex a = fy[iy];
      for (std::size_t ix = 0; ix < n_; ++ix) row[ix] *= a * fx[ix];
    }
  }

  std::size_t n_;
  double d2_, scale_out_ = 1.0;
  std::vector<Complex> in_x_, in_y_, q2_, q3_;
};

}  // namespace lidar_overlap::detail
