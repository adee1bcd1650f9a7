#include "lidar_overlap/beams/flat_top.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "lidar_overlap/core/limits.hpp"
#include "core/cancel_every.hpp"
#include "core/checks.hpp"
#include "core/constants.hpp"
#include "core/parallel.hpp"
#include "fourier/fft.hpp"

namespace lidar_overlap {

namespace {

// Angle (rad) of FFT-order index i on n samples of spacing dx.
double angle_of(std::size_t i, std::size_t n, double dx, double wavelength) {
  const double k =
      i < n / 2 ? static_cast<double>(i) : static_cast<double>(i) - static_cast<double>(n);
  return wavelength * k / (static_cast<double>(n) * dx);
}

// FFT order -> centred (index n/2 is zero), for an even n.
std::vector<double> centred(const std::vector<double>& fft_order, std::size_t n) {
  std::vector<double> out(n * n);
  for (std::size_t iy = 0; iy < n; ++iy)
    for (std::size_t ix = 0; ix < n; ++ix)
      out[((iy + n / 2) % n) * n + (ix + n / 2) % n] = fft_order[iy * n + ix];
  return out;
}

// 10-90 % width of the azimuthal average of `intensity` (centred) about the centre, normalised to
// `plateau`; radial bins of one sample.
double edge_width_of(const std::vector<double>& intensity, std::size_t n, double plateau,
                     double spacing) {
  std::vector<double> sum(n, 0.0), count(n, 0.0);
  for (std::size_t iy = 0; iy < n; ++iy)
    for (std::size_t ix = 0; ix < n; ++ix) {
      const double r =
          std::hypot(static_cast<double>(ix) - n / 2.0, static_cast<double>(iy) - n / 2.0);
      const std::size_t b = static_cast<std::size_t>(std::lround(r));
      if (b < n) sum[b] += intensity[iy * n + ix], count[b] += 1.0;
    }
  std::vector<double> profile(n / 2);
  for (std::size_t b = 0; b < profile.size(); ++b) profile[b] = sum[b] / count[b] / plateau;
  // Outermost crossings going outwards: last bin at or above the level, interpolated to the next one.
  auto crossing = [&](double level) {
    std::size_t b = profile.size() - 1;
    while (b > 0 && profile[b] < level) --b;
    if (b + 1 >= profile.size()) return static_cast<double>(b);
    return b + (profile[b] - level) / (profile[b] - profile[b + 1]);
  };
  return (crossing(0.1) - crossing(0.9)) * spacing;
}

}  // namespace

const char* to_string(FlatTopStop stop) {
  switch (stop) {
    case FlatTopStop::converged:
      return "converged";
    case FlatTopStop::stagnated:
      return "stagnated";
    default:
      return "max_iterations";
  }
}

FlatTopDesign design_flat_top(double wavelength, double waist_radius, double angular_diameter,
                              const FlatTopOptions& o) {
  checks::length("wavelength", wavelength);
  checks::length("waist_radius", waist_radius);
  checks::positive("angular_diameter", angular_diameter);
  checks::angle("angular_diameter", 0.5 * angular_diameter);
  checks::positive("samples_per_waist", o.samples_per_waist);
  checks::non_negative("edge_width", o.edge_width);
  checks::in_open_unit("tolerance", o.tolerance);
  checks::positive("max_error", o.max_error);
  checks::positive("power", o.power);
  if (o.max_iterations < 1 || o.max_iterations > 100000)
    checks::fail("max_iterations", static_cast<double>(o.max_iterations),
                 "a count from 1 to 100000");
  const std::size_t n = o.grid;
  if (n < 64 || n % 2) checks::fail("grid", static_cast<double>(n), "an even size >= 64");
  checks::grid("grid", n, sizeof(double),
               12);  // the fields, targets and angle maps of the iteration
  const double theta_d = wavelength / (kPi * waist_radius);  // TEM00 half-angle divergence
  if (angular_diameter <= 2.0 * theta_d)
    checks::fail(
        "angular_diameter", angular_diameter,
        "more than the TEM00 beam's own full divergence 2 lambda / (pi w0) = " +
            std::to_string(2.0 * theta_d) +
            " rad: a phase plate can only spread the beam; enlarge waist_radius for a narrower disc");
  const double dx = waist_radius / o.samples_per_waist, dtheta = wavelength / (n * dx);
  const double edge = o.edge_width > 0.0 ? o.edge_width : 1.5 * theta_d,
               half = 0.5 * angular_diameter;
  if (n * dx < 8.0 * waist_radius)
    checks::fail("grid", static_cast<double>(n),
                 "at least 8 samples_per_waist = " + std::to_string(8.0 * o.samples_per_waist) +
                     " to hold the beam");
  if (half + 2.0 * edge > 0.5 * wavelength / dx)
    checks::fail(
        "samples_per_waist", o.samples_per_waist,
        "a sampling whose Nyquist angle lambda / (2 dx) exceeds the disc and its edge: at most " +
            std::to_string(wavelength * waist_radius / (2.0 * dx) / (half + 2.0 * edge) *
                           o.samples_per_waist));
  if (half < 8.0 * dtheta)
    checks::fail("grid", static_cast<double>(n),
                 "a grid giving at least 8 far-field samples across the disc radius (" +
                     std::to_string(8.0 * n * dtheta / half) + " or more)");

  FlatTopDesign d;
  d.angular_spacing = dtheta;
  d.edge_width_target = edge;
  d.transmitted = Field::gaussian(wavelength, waist_radius, n, dx, {}, o.power);
  std::vector<double> amplitude(n * n), target(n * n),
      far_angle(n * n);  // far_angle: rad, FFT order
  for (std::size_t i = 0; i < n * n; ++i)
    amplitude[i] = d.transmitted.values[i].real();  // real at the waist
  // Fermi-Dirac edge: 10-90 % over 2 ln 9 s.
  const double s = edge / (2.0 * std::log(9.0));
  double target_sum = 0.0, field_sum = 0.0;
  for (std::size_t iy = 0; iy < n; ++iy) {
    detail::cancellation_point();  // once per row: a 4096² grid takes seconds on a busy core
    for (std::size_t ix = 0; ix < n; ++ix) {
      const double theta = far_angle[iy * n + ix] =
          std::hypot(angle_of(ix, n, dx, wavelength), angle_of(iy, n, dx, wavelength));
      target[iy * n + ix] = 1.0 / (1.0 + std::exp((theta - half) / s));
      target_sum += target[iy * n + ix];
    }
  }
  for (std::size_t i = 0; i < n * n; ++i) {
    detail::cancellation_point_every(i);
    field_sum += amplitude[i] * amplitude[i];
  }
  // Same power in both planes (the unnormalised FFT multiplies sum |u|^2 by n^2): B = sqrt(T) scaled.
  std::vector<double> b(n * n);
  const double scale = std::sqrt(field_sum * n * n / target_sum);
  double b_norm = 0.0;
  for (std::size_t i = 0; i < n * n; ++i) {
    detail::cancellation_point_every(i);
    b_norm += (b[i] = scale * std::sqrt(target[i])) * b[i];
  }

  // Start from the ray-optics plate, which maps the enclosed power of the Gaussian, 1 - exp(-2 r^2 / w0^2),
  // onto that of a uniform disc, (theta / theta_max)^2: theta(r) = theta_max sqrt(1 - exp(-2 r^2 / w0^2)),
  // phase k int theta dr. GS then only corrects diffraction (10 iterations instead of ~100 from a flat one).
  ComplexBuffer u = d.transmitted.values;
  {
    const std::size_t m = 4 * n;
    const double r_max = dx * n, dr = r_max / m, k = 2.0 * kPi / wavelength;
    std::vector<double> ray_phase(m + 2, 0.0);
    auto theta = [&](double r) {
      return half * std::sqrt(-std::expm1(-2.0 * r * r / (waist_radius * waist_radius)));
    };
    for (std::size_t i = 1; i < ray_phase.size(); ++i)
      ray_phase[i] = ray_phase[i - 1] + 0.5 * k * dr * (theta((i - 1) * dr) + theta(i * dr));
    for (std::size_t iy = 0; iy < n; ++iy) {
      detail::cancellation_point();
      for (std::size_t ix = 0; ix < n; ++ix) {
        const double pos =
            std::hypot(d.transmitted.coordinate(ix), d.transmitted.coordinate(iy)) / dr;
        const std::size_t i = static_cast<std::size_t>(pos);
        const double phase = ray_phase[i] + (pos - i) * (ray_phase[i + 1] - ray_phase[i]);
        u[iy * n + ix] = std::polar(amplitude[iy * n + ix], std::remainder(phase, 2.0 * kPi));
      }
    }
  }
  // Error reduction: impose the far-field amplitude, then the plate-plane amplitude, keeping the phases.
  auto with_modulus = [](Complex v, double m) {
    const double a = std::sqrt(std::norm(v));
    return a > 0.0 ? v * (m / a) : Complex{m, 0.0};
  };
  for (std::size_t it = 0;; ++it) {
    detail::cancellation_point();
    fft2d(u, n, FftDirection::forward);
    double err = 0.0;
    for (std::size_t i = 0; i < n * n; ++i) {
      detail::cancellation_point_every(i);  // a 4096² grid has 16.8 M samples
      const double a = std::sqrt(std::norm(u[i]));
      err += (a - b[i]) * (a - b[i]);
    }
    err = std::sqrt(err / b_norm);
    d.history.push_back(err);
    if (it > 0 && err > d.history[it - 1] * (1.0 + 1e-12)) d.monotone = false;
    const bool settled = it > 0 && d.history[it - 1] - err <= o.tolerance * err;
    if (settled || it + 1 >= o.max_iterations) {
      d.stop = !settled             ? FlatTopStop::max_iterations
               : err <= o.max_error ? FlatTopStop::converged
                                    : FlatTopStop::stagnated;
      break;  // u holds the far field of the current plate
    }
    for (std::size_t i = 0; i < n * n; ++i) {
      detail::cancellation_point_every(i);
      u[i] = with_modulus(u[i], b[i]);
    }
    fft2d(u, n, FftDirection::backward);
    for (std::size_t i = 0; i < n * n; ++i) {
      detail::cancellation_point_every(i);
      u[i] = with_modulus(u[i], amplitude[i]);
    }
  }

  // The plate is the phase of the last plate-plane field (the one whose far field was just measured).
  ComplexBuffer plate = u;
  fft2d(plate, n, FftDirection::backward);
  d.phase.resize(n * n);
  for (std::size_t i = 0; i < n * n; ++i) {
    detail::cancellation_point_every(i);  // a 4096² grid has 16.8 M samples
    d.phase[i] = std::arg(plate[i]);
    d.transmitted.values[i] = std::polar(amplitude[i], d.phase[i]);
  }
  // Radiant intensity J = |dx^2 FFT|^2 / lambda^2 (W/sr): sum J dtheta^2 is the power.
  const double to_w_per_sr = std::pow(dx, 4) / (wavelength * wavelength);
  std::vector<double> j(n * n), t(n * n);
  for (std::size_t i = 0; i < n * n; ++i) {
    detail::cancellation_point_every(i);
    j[i] = std::norm(u[i]) * to_w_per_sr, t[i] = b[i] * b[i] * to_w_per_sr;
  }
  d.far_field = centred(j, n);
  d.target = centred(t, n);

  double inside = 0.0, total = 0.0, sum = 0.0, sum2 = 0.0, lo = INFINITY, hi = 0.0, count = 0.0;
  for (std::size_t i = 0; i < n * n; ++i) {
    detail::cancellation_point_every(i);  // a 4096² grid has 16.8 M samples
    total += j[i];
    if (far_angle[i] <= half) inside += j[i];
    if (target[i] >= 0.9) {
      sum += j[i], sum2 += j[i] * j[i], count += 1.0;
      lo = std::min(lo, j[i]), hi = std::max(hi, j[i]);
    }
  }
  const double mean = sum / count;
  d.efficiency = inside / total;
  d.uniformity_rms = std::sqrt(std::max(0.0, sum2 / count - mean * mean)) / mean;
  d.uniformity_pv = (hi - lo) / mean;
  d.edge_width = edge_width_of(d.far_field, n, mean, dtheta);
  return d;
}

}  // namespace lidar_overlap
