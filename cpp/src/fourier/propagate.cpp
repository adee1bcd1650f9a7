#include "lidar_overlap/fourier/propagate.hpp"

#include <algorithm>
#include <cmath>
#include <list>
#include <mutex>
#include <tuple>

#include "lidar_overlap/core/limits.hpp"
#include "core/checks.hpp"
#include "core/cancel_every.hpp"
#include "core/constants.hpp"
#include "core/parallel.hpp"
#include "core/team.hpp"
#include "fourier/fft.hpp"
#include "fourier/extent_sums.hpp"
#include "fourier/fft_passes.hpp"
#include "fourier/line_products.hpp"
#include "fourier/scaled_dft.hpp"
#include "fourier/zeroed_buffer.hpp"

namespace lidar_overlap {

using detail::Extent;
using detail::ExtentSums;

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

// Per-axis chirp exp(i k x^2 / 2z) on a centred grid, times (-1)^i when `centring` (the sign that
// turns an FFT into a centred DFT for even n): its n real parts, then its n imaginary parts.
std::vector<double> axis_chirp(std::size_t n, double dx, double k, double z, bool centring) {
  std::vector<double> c(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = (static_cast<double>(i) - 0.5 * n) * dx;
    const Complex v = unit_phasor(0.5 * k * x * x / z) * ((centring && i % 2) ? -1.0 : 1.0);
    c[i] = v.real();
    c[n + i] = v.imag();
  }
  return c;
}

// Value i of a chirp split by axis_chirp.
Complex chirp_at(const std::vector<double>& chirp, std::size_t i) {
  return {chirp[i], chirp[chirp.size() / 2 + i]};
}

// u[iy, ix] *= scale * a[iy] * a[ix] (a chirp split by axis_chirp), and the Extent of the result (the
// chirp-z path's multiplications).
Extent apply_separable(ComplexBuffer& u, std::size_t n, const std::vector<double>& a,
                       Complex scale) {
  const int threads = fft_threads(n * n);
  ExtentSums sums(n, threads, true);
  detail::for_each_block(static_cast<long>(n), threads, [&](long b) {  // a block is a line
    const std::size_t iy = static_cast<std::size_t>(b);
    Complex* line = u.data() + iy * n;
    sums.add_product(iy, line, scale * chirp_at(a, iy), a, line);
  });
  return sums.result();
}

void require_finite(double power, double distance) {
  if (!std::isfinite(power))
    throw std::domain_error(
        "propagate: the field holds non-finite values after " + checks::number(distance) +
        " m: its input was not finite, or the distance and sampling leave double precision");
}

// The Fresnel and Fraunhofer report from the extents of the input and the output.
void fresnel_report(PropagationReport& r, const Extent& before, const Extent& after,
                    bool scaled_output, double spacing, double output_spacing, double wavelength,
                    double distance) {
  require_finite(after.total, distance);
  r.input_edge_power = before.edge_fraction();
  r.output_edge_power = after.edge_fraction();
  r.scaled_output = scaled_output;
  // Extents about the optical axis, where A3 and A6 measure them.
  const double a_in = before.radius(kSupportFraction, spacing);
  const double a_out = after.radius(kSupportFraction, output_spacing);
  const double k = 2.0 * kPi / wavelength;
  r.chirp_phase_step = r.method == PropagationMethod::fresnel ? k * a_in * spacing / distance : 0.0;
  r.fresnel_phase_error =
      kPi / (4.0 * wavelength) * std::pow(a_in + a_out, 4) / std::pow(distance, 3);
  r.fraunhofer_phase = kPi * a_in * a_in / (wavelength * distance);
}

}  // namespace

PropagationPlan::PropagationPlan(std::size_t n, double spacing, double wavelength, double distance,
                                 PropagationMethod method, double output_spacing)
    : n_(n),
      spacing_(spacing),
      wavelength_(wavelength),
      distance_(distance),
      output_spacing_(output_spacing) {
  if (n < 8 || n % 2 != 0 || n > kMaxGridSide)
    checks::fail("field.n", static_cast<double>(n),
                 "an even grid size from 8 to " + std::to_string(kMaxGridSide));
  checks::grid("field.n", n, sizeof(Complex),
               3);  // the field, the transfer function or chirps, a copy
  checks::length("field.spacing", spacing);
  checks::length("field.wavelength", wavelength);
  checks::coordinate("distance", distance);
  checks::non_negative("output_spacing", output_spacing);
  if (output_spacing > 0.0) checks::length("output_spacing", output_spacing);
  critical_distance_ = n * spacing * spacing / wavelength;
  if (method == PropagationMethod::automatic) {
    const bool natural_as = output_spacing == 0.0 || output_spacing == spacing;
    method = (natural_as && std::abs(distance) <= critical_distance_)
                 ? PropagationMethod::angular_spectrum
                 : PropagationMethod::fresnel;
  }
  if (distance == 0.0) method = PropagationMethod::angular_spectrum;  // the identity
  method_ = method;
  const double k = 2.0 * kPi / wavelength, z = distance;

  if (method == PropagationMethod::angular_spectrum) {
    if (output_spacing != 0.0 && output_spacing != spacing)
      checks::fail(
          "output_spacing", output_spacing,
          "0 or the input spacing for the angular spectrum method (its output grid is the input grid)");
    output_spacing_ = spacing;
    // A1: exp(i k z sqrt(1 - lambda^2 f^2)), zero for evanescent waves and beyond the band limit
    // 1 / (lambda sqrt((2 df z)^2 + 1)) where its phase would alias on the frequency grid. The FFT
    // normalisation 1/n^2 is folded in.
    const double df = 1.0 / (n * spacing);
    const double f_limit = 1.0 / (wavelength * std::sqrt(std::pow(2.0 * df * z, 2) + 1.0));
    const Complex carrier = unit_phasor(k * z) / static_cast<double>(n * n);
    transfer_ = detail::zeroed_buffer(n * n);  // zeroed in chunks, each after a cancellation point
    const int threads = fft_threads(n * n);
    detail::RegionStop stop;  // n^2 phasors: seconds for a 16384^2 grid on a busy core
#pragma omp parallel for num_threads(threads) if (threads > 1)
    for (long iy = 0; iy < static_cast<long>(n); ++iy) {
      if (stop.stopped()) continue;
      const double fy = frequency(iy, n, spacing);
      for (std::size_t ix = 0; ix < n; ++ix) {
        const double fx = frequency(ix, n, spacing);
        const double s = wavelength * wavelength * (fx * fx + fy * fy);
        if (s >= 1.0 || std::abs(fx) > f_limit || std::abs(fy) > f_limit) continue;
        // k z (sqrt(1 - s) - 1) without cancellation.
        transfer_[iy * n + ix] = carrier * unit_phasor(-k * z * s / (1.0 + std::sqrt(1.0 - s)));
      }
    }
    stop.rethrow();
    return;
  }

  if (!(distance > 0.0))
    checks::fail("distance", distance, "a distance > 0 for Fresnel and Fraunhofer propagation");
  const double natural = wavelength * z / (n * spacing);
  if (output_spacing_ == 0.0) output_spacing_ = natural;
  single_fft_ = std::abs(output_spacing_ / natural - 1.0) < 1e-12;
  // A5 / A7: U2(x) = exp(ikz)/(i lambda z) exp(ik x^2/2z) dx^2 DFT[U1 (exp(ik xi^2/2z) for A5)].
  if (method == PropagationMethod::fresnel)
    chirp_in_ = axis_chirp(n, spacing, k, z, single_fft_);
  else if (single_fft_)
    chirp_in_ = axis_chirp(n, spacing, 0.0, z, true);  // the centring sign only
  chirp_out_ = axis_chirp(n, output_spacing_, k, z, single_fft_);
  front_ = unit_phasor(k * z) * Complex(0.0, -1.0) * (spacing * spacing / (wavelength * z));
}

std::shared_ptr<const PropagationPlan> PropagationPlan::cached(std::size_t n, double spacing,
                                                               double wavelength, double distance,
                                                               PropagationMethod method,
                                                               double output_spacing) {
  using Key = std::tuple<std::size_t, double, double, double, int, double>;
  static std::mutex mutex;
  static std::list<std::pair<Key, std::shared_ptr<const PropagationPlan>>>
      recent;  // most recent first
  constexpr std::size_t kCapacity = 16;
  const Key key{n, spacing, wavelength, distance, static_cast<int>(method), output_spacing};
  {
    std::lock_guard<std::mutex> lock(mutex);
    for (auto it = recent.begin(); it != recent.end(); ++it)
      if (it->first == key) {
        recent.splice(recent.begin(), recent, it);
        return recent.front().second;
      }
  }
  auto plan = std::make_shared<const PropagationPlan>(n, spacing, wavelength, distance, method,
                                                      output_spacing);
  std::lock_guard<std::mutex> lock(mutex);
  recent.emplace_front(key, plan);
  // At most kCapacity plans and kCapacityBytes of tables (a transfer function of 8192^2 is 1 GiB): the least
  // recently used go first, the newest stays.
  constexpr std::size_t kCapacityBytes = std::size_t{1} << 30;
  auto bytes = [](const PropagationPlan& p) {
    return sizeof(Complex) * p.transfer_.size() +
           sizeof(double) * (p.chirp_in_.size() + p.chirp_out_.size());
  };
  std::size_t total = 0;
  for (const auto& entry : recent) total += bytes(*entry.second);
  while (recent.size() > 1 && (recent.size() > kCapacity || total > kCapacityBytes)) {
    total -= bytes(*recent.back().second);
    recent.pop_back();
  }
  return plan;
}

Propagated PropagationPlan::execute(Field in) const {
  in.validate();
  if (in.n != n_ || in.spacing != spacing_ || in.wavelength != wavelength_)
    checks::fail("field.n", static_cast<double>(in.n),
                 "the grid, spacing and wavelength the plan was made for");
  Propagated out;
  ComplexBuffer& u = in.values;  // the field is ours: transform it in place
  out.report = single_fft_ || method_ == PropagationMethod::angular_spectrum
                   ? execute(u.data(), u.data())
                   : scaled(u);
  out.field = Field{std::move(u), n_, output_spacing_, wavelength_};
  return out;
}

PropagationReport PropagationPlan::execute(const Complex* in, Complex* out) const {
  PropagationReport r;
  r.method = method_;
  r.critical_distance = critical_distance_;
  const std::size_t n = n_;
  const int threads = fft_threads(n * n);

  if (method_ == PropagationMethod::angular_spectrum) {
    // Three passes over the field: forward rows (from `in`, the input's sums on the way), then per block of
    // columns the forward column transforms, the transfer function and the backward column transforms while
    // the block is in cache, then backward rows (the output's sums). The transfer function is symmetric in
    // (fx, fy), so column kx reads it contiguously at transfer_[kx * n + ky].
    ExtentSums input(n, threads, false), output(n, threads, false);
    if (distance_ == 0.0) {
      for (std::size_t iy = 0; iy < n; ++iy) {
        detail::cancellation_point_every(iy);
        input.add(iy, in + iy * n);
        if (out != in) std::copy(in + iy * n, in + (iy + 1) * n, out + iy * n);
      }
      output = input;
    } else {
      detail::cancellation_point();
      std::vector<double> spectrum(n), removed(n);
      // Out of place throughout (FFTW's in-place plans copy through a buffer of their own): rows from a
      // per-thread block (or straight from the caller's rows when they are another aligned array), columns
      // through a one-column buffer.
      if (in != out && fftw_aligned(in))
        detail::row_pass_from(in, out, n, n, FftDirection::forward, threads,
                              [&](std::size_t iy, const Complex* row) { input.add(iy, row); });
      else
        detail::row_pass_into(
            out, n, n, FftDirection::forward, threads,
            [&](std::size_t iy, Complex* line) {
              std::copy(in + iy * n, in + (iy + 1) * n, line);
              input.add(iy, line);
            },
            [](std::size_t, Complex*) {});
      const BlockTransform forward(n, FftDirection::forward, n),
          backward(n, FftDirection::backward, n);
      detail::column_pass(out, n, n, threads,
                          [&](std::size_t x0, std::size_t count, Complex* block) {
                            const std::size_t stride = detail::column_stride(n);
                            Complex* k = detail::column_buffer(n);
                            for (std::size_t c = 0; c < count; ++c) {
                              Complex* column = block + c * stride;
                              forward(column, k, 1);
                              const Complex* h = transfer_.data() + (x0 + c) * n;
                              // Only the band edge is zero: the power it removes is summed where h vanishes, the rest multiplied.
                              double cut = 0.0;
                              spectrum[x0 + c] = detail::power(k, n);
                              for (std::size_t ky = 0; ky < n; ++ky) {
                                if (h[ky] == Complex{}) cut += std::norm(k[ky]);
                                k[ky] = detail::product(k[ky], h[ky]);
                              }
                              removed[x0 + c] = cut;
                              backward(k, column, 1);
                            }
                          });
      const Complex* spectrum_rows = out;
      detail::row_pass_into(
          out, n, n, FftDirection::backward, threads,
          [&](std::size_t iy, Complex* line) {
            std::copy(spectrum_rows + iy * n, spectrum_rows + (iy + 1) * n, line);
          },
          [&](std::size_t iy, Complex* line) { output.add(iy, line); });
      double spectrum_total = 0.0, removed_total = 0.0;
      for (std::size_t k = 0; k < n; ++k) {
        spectrum_total += spectrum[k];
        removed_total += removed[k];
      }
      r.band_limit_loss = spectrum_total > 0.0 ? removed_total / spectrum_total : 0.0;
    }
    const Extent before = input.result(), after = output.result();
    require_finite(after.total, distance_);
    r.input_edge_power = before.edge_fraction();
    r.output_edge_power = after.edge_fraction();
    return r;
  }

  if (!single_fft_) {  // the chirp-z path works on a buffer of its own
    ComplexBuffer u(in, in + n * n);
    r = scaled(u);
    std::copy(u.begin(), u.end(), out);
    return r;
  }
  // One forward transform: the input chirp applied to each row before its transform, the output chirp
  // and front factor to each column after its transform, the sums of both on the way.
  detail::cancellation_point();
  ExtentSums input(n, threads, true), output(n, threads, true);
  // Both passes out of place (FFTW's in-place plans copy through a buffer of their own): each row of `in`,
  // chirped, into a block that is transformed into the rows of `out`; each gathered column into a one-column
  // buffer, chirped on its way back.
  detail::row_pass_into(
      out, n, n, FftDirection::forward, threads,
      [&](std::size_t iy, Complex* line) {
        input.add_product(iy, in + iy * n, chirp_at(chirp_in_, iy), chirp_in_, line);
      },
      [](std::size_t, Complex*) {});
  const BlockTransform columns(n, FftDirection::forward, n);
  detail::column_pass(out, n, n, threads, [&](std::size_t x0, std::size_t count, Complex* block) {
    const std::size_t stride = detail::column_stride(n);
    Complex* transformed = detail::column_buffer(n);
    for (std::size_t c = 0; c < count; ++c) {
      Complex* column = block + c * stride;
      columns(column, transformed, 1);
      output.add_product(x0 + c, transformed, front_ * chirp_at(chirp_out_, x0 + c), chirp_out_,
                         column);
    }
  });
  fresnel_report(r, input.result(), output.result(), false, spacing_, output_spacing_, wavelength_,
                 distance_);
  return r;
}

PropagationReport PropagationPlan::scaled(ComplexBuffer& u) const {
  PropagationReport r;
  r.method = method_;
  r.critical_distance = critical_distance_;
  std::vector<double> unit(2 * n_, 0.0);  // 1 + 0i, split
  std::fill(unit.begin(), unit.begin() + n_, 1.0);
  const Extent before = apply_separable(u, n_, chirp_in_.empty() ? unit : chirp_in_, 1.0);
  u = scaled_dft2d(u, n_, n_, spacing_ * output_spacing_ / (wavelength_ * distance_));
  const Extent after = apply_separable(u, n_, chirp_out_, front_);
  fresnel_report(r, before, after, true, spacing_, output_spacing_, wavelength_, distance_);
  return r;
}

Propagated propagate(Field in, double distance, PropagationMethod method, double output_spacing) {
  const auto plan =
      PropagationPlan::cached(in.n, in.spacing, in.wavelength, distance, method, output_spacing);
  return plan->execute(std::move(in));  // which checks that the output is finite
}

}  // namespace lidar_overlap
