#include "lidar_overlap/propagate.hpp"

#include <cmath>

#include "lidar_overlap/checks.hpp"
#include "lidar_overlap/constants.hpp"
#include "lidar_overlap/scaled_dft.hpp"

namespace lidar_overlap {

namespace {

// Fraction of power that decides a field's extent for the validity checks.
constexpr double kSupportFraction = 1.0 - 1e-6;

// exp(i phase) with the phase reduced first: k z is ~1e11 rad at lidar ranges.
Complex unit_phasor(double phase) {
  const double p = std::remainder(phase, 2.0 * kPi);
  return {std::cos(p), std::sin(p)};
}

// FFT frequency of index i on n samples of spacing dx (FFTW order).
double frequency(std::size_t i, std::size_t n, double dx) {
  const long k = i < n / 2 ? static_cast<long>(i) : static_cast<long>(i) - static_cast<long>(n);
  return static_cast<double>(k) / (static_cast<double>(n) * dx);
}

// A1 with the transfer function exp(i k z sqrt(1 - lambda^2 f^2)), zero for evanescent waves and beyond
// the band limit 1 / (lambda sqrt((2 df z)^2 + 1)) where its phase would alias on the frequency grid.
Propagated angular_spectrum(const Field& in, double z) {
  const std::size_t n = in.n;
  const double dx = in.spacing, lambda = in.wavelength, k = 2.0 * kPi / lambda;
  const double df = 1.0 / (n * dx);
  const double f_limit = 1.0 / (lambda * std::sqrt(std::pow(2.0 * df * z, 2) + 1.0));
  ComplexBuffer u = in.values;
  fft2d(u, n, FftDirection::forward);
  double total = 0.0, removed = 0.0;
  const Complex carrier = unit_phasor(k * z);
#pragma omp parallel for reduction(+ : total, removed)
  for (long iy = 0; iy < static_cast<long>(n); ++iy) {
    const double fy = frequency(iy, n, dx);
    for (std::size_t ix = 0; ix < n; ++ix) {
      const double fx = frequency(ix, n, dx);
      Complex& v = u[iy * n + ix];
      const double p = std::norm(v);
      total += p;
      const double s = lambda * lambda * (fx * fx + fy * fy);
      if (s >= 1.0 || std::abs(fx) > f_limit || std::abs(fy) > f_limit) {
        removed += p;
        v = 0.0;
        continue;
      }
      // k z (sqrt(1 - s) - 1) without cancellation; the carrier exp(i k z) is applied separately.
      v *= carrier * unit_phasor(-k * z * s / (1.0 + std::sqrt(1.0 - s))) / static_cast<double>(n * n);
    }
  }
  fft2d(u, n, FftDirection::backward);
  Propagated out{Field{std::move(u), n, dx, lambda}, {}};
  out.report.method = PropagationMethod::angular_spectrum;
  out.report.band_limit_loss = total > 0.0 ? removed / total : 0.0;
  return out;
}

// A5 (with_input_chirp) or A7: U2(x) = exp(ikz)/(i lambda z) exp(ik x^2/2z) dx^2 DFT[U1 exp(ik xi^2/2z)],
// output spacing dx2; the single-FFT case is the scaled DFT with alpha = 1/n.
Propagated fresnel_family(const Field& in, double z, double dx2, bool with_input_chirp) {
  const std::size_t n = in.n;
  const double dx = in.spacing, lambda = in.wavelength, k = 2.0 * kPi / lambda;
  ComplexBuffer u = in.values;
  if (with_input_chirp) {
#pragma omp parallel for
    for (long iy = 0; iy < static_cast<long>(n); ++iy)
      for (std::size_t ix = 0; ix < n; ++ix) {
        const double x = in.coordinate(ix), y = in.coordinate(iy);
        u[iy * n + ix] *= unit_phasor(0.5 * k * (x * x + y * y) / z);
      }
  }
  const double alpha = dx * dx2 / (lambda * z);
  ComplexBuffer v;
  if (std::abs(alpha * n - 1.0) < 1e-12) {
    // Centred DFT by FFT: modulate by (-1)^(ix + iy) before and after (n even).
    for (std::size_t iy = 0; iy < n; ++iy)
      for (std::size_t ix = 0; ix < n; ++ix)
        if ((ix + iy) % 2) u[iy * n + ix] = -u[iy * n + ix];
    fft2d(u, n, FftDirection::forward);
    for (std::size_t iy = 0; iy < n; ++iy)
      for (std::size_t ix = 0; ix < n; ++ix)
        if ((ix + iy) % 2) u[iy * n + ix] = -u[iy * n + ix];
    v = std::move(u);
  } else {
    v = scaled_dft2d(u, n, n, alpha);
  }
  Field out{std::move(v), n, dx2, lambda};
  const Complex front = unit_phasor(k * z) * Complex(0.0, -1.0) * (dx * dx / (lambda * z));
#pragma omp parallel for
  for (long iy = 0; iy < static_cast<long>(n); ++iy)
    for (std::size_t ix = 0; ix < n; ++ix) {
      const double x = out.coordinate(ix), y = out.coordinate(iy);
      out.values[iy * n + ix] *= front * unit_phasor(0.5 * k * (x * x + y * y) / z);
    }
  Propagated result{std::move(out), {}};
  result.report.method = with_input_chirp ? PropagationMethod::fresnel : PropagationMethod::fraunhofer;
  return result;
}

}  // namespace

Propagated propagate(const Field& in, double distance, PropagationMethod method, double output_spacing) {
  in.validate();
  checks::finite("distance", distance);
  checks::non_negative("output_spacing", output_spacing);
  const double critical = in.n * in.spacing * in.spacing / in.wavelength;
  if (method == PropagationMethod::automatic) {
    const bool natural_as = output_spacing == 0.0 || output_spacing == in.spacing;
    method = (natural_as && std::abs(distance) <= critical) ? PropagationMethod::angular_spectrum
                                                            : PropagationMethod::fresnel;
  }
  if (method != PropagationMethod::angular_spectrum && !(distance > 0.0))
    checks::fail("distance", distance, "a distance > 0 for Fresnel and Fraunhofer propagation");
  if (method == PropagationMethod::angular_spectrum && output_spacing != 0.0 && output_spacing != in.spacing)
    checks::fail("output_spacing", output_spacing,
                 "0 or the input spacing for the angular spectrum method (its output grid is the input grid)");

  Propagated out;
  if (distance == 0.0) {
    out = {in, {}};
    out.report.method = PropagationMethod::angular_spectrum;
  } else if (method == PropagationMethod::angular_spectrum) {
    out = angular_spectrum(in, distance);
  } else {
    const double natural = in.wavelength * distance / (in.n * in.spacing);
    out = fresnel_family(in, distance, output_spacing > 0.0 ? output_spacing : natural,
                         method == PropagationMethod::fresnel);
  }

  PropagationReport& r = out.report;
  r.critical_distance = critical;
  r.input_edge_power = in.edge_power_fraction();
  r.output_edge_power = out.field.edge_power_fraction();
  if (r.method != PropagationMethod::angular_spectrum) {
    const double a_in = in.support_radius(kSupportFraction);
    const double a_out = out.field.support_radius(kSupportFraction);
    const double k = 2.0 * kPi / in.wavelength;
    r.chirp_phase_step = r.method == PropagationMethod::fresnel ? k * a_in * in.spacing / distance : 0.0;
    r.fresnel_phase_error = kPi / (4.0 * in.wavelength) * std::pow(a_in + a_out, 4) / std::pow(distance, 3);
    r.fraunhofer_phase = kPi * a_in * a_in / (in.wavelength * distance);
  }
  return out;
}

}  // namespace lidar_overlap
