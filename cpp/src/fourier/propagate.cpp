#include "lidar_overlap/fourier/propagate.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <list>
#include <mutex>
#include <tuple>

#include "lidar_overlap/core/limits.hpp"
#include "core/checks.hpp"
#include "core/constants.hpp"
#include "fourier/fft.hpp"
#include "fourier/scaled_dft.hpp"

namespace lidar_overlap {

namespace {

// Grids from this side up are worth splitting across threads (smaller ones lose more to start-up and
// to other processes than they gain).
constexpr std::size_t kParallelSide = 1024;

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
// turns an FFT into a centred DFT for even n).
std::vector<Complex> axis_chirp(std::size_t n, double dx, double k, double z, bool centring) {
  std::vector<Complex> c(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = (static_cast<double>(i) - 0.5 * n) * dx;
    c[i] = unit_phasor(0.5 * k * x * x / z) * ((centring && i % 2) ? -1.0 : 1.0);
  }
  return c;
}

// What the validity checks need of a field, gathered in a pass that has other work to do: total
// power, power in the outer n/16 of the window, and the power per squared radius about the optical
// axis (bins of n/8 samples^2: no square root per sample, and a quarter sample of radius at r = n/4),
// taken on every other row and column.
struct Extent {
  double total = 0.0, border = 0.0;
  std::size_t n;
  std::vector<double> radial;
  explicit Extent(std::size_t n_) : n(n_), radial(4 * n_ + 2, 0.0) {}
  std::size_t bin(double r2) const { return std::min(radial.size() - 1, static_cast<std::size_t>(r2 * 8.0 / n)); }
  double edge_fraction() const { return total > 0.0 ? border / total : 0.0; }
  // Radius (m) holding `fraction` of the (sampled) radial profile's power, for samples of spacing dx.
  double radius(double fraction, double dx) const {
    double sampled = 0.0, inside = 0.0;
    for (double p : radial) sampled += p;
    for (std::size_t b = 0; b < radial.size(); ++b) {
      inside += radial[b];
      if (inside >= fraction * sampled) return dx * std::sqrt((b + 1) * n / 8.0);
    }
    return dx * std::sqrt(radial.size() * n / 8.0);
  }
};

// u[iy, ix] *= scale * a[iy] * a[ix], and the Extent of the result.
Extent apply_separable(ComplexBuffer& u, std::size_t n, const std::vector<Complex>& a, Complex scale) {
  Extent e(n);
  const std::size_t border = std::max<std::size_t>(1, n / 16);
  const double half = 0.5 * static_cast<double>(n);
#pragma omp parallel if (n >= kParallelSide)
  {
    Extent mine(n);  // per thread, merged once: shared accumulators would bounce between caches
#pragma omp for
    for (long iy = 0; iy < static_cast<long>(n); ++iy) {
      const Complex row = scale * a[iy];
      const bool edge_row = static_cast<std::size_t>(iy) < border || static_cast<std::size_t>(iy) >= n - border;
      Complex* line = u.data() + iy * n;
      double total = 0.0, edge = 0.0;
      for (std::size_t ix = 0; ix < n; ++ix) {
        line[ix] *= row * a[ix];
        total += std::norm(line[ix]);
      }
      for (std::size_t ix = 0; ix < border; ++ix) edge += std::norm(line[ix]) + std::norm(line[n - 1 - ix]);
      mine.total += total;
      mine.border += edge_row ? total : edge;
      // The radial profile only bounds the extent for the validity checks: every other row and column
      // (weighted 4) resolve it to two samples at a quarter of the cost.
      if (iy % 2) continue;
      const double y2 = (iy - half) * (iy - half);
      for (std::size_t ix = 0; ix < n; ix += 2) {
        const double x = ix - half;
        mine.radial[mine.bin(x * x + y2)] += 4.0 * std::norm(line[ix]);
      }
    }
#pragma omp critical
    {
      e.total += mine.total;
      e.border += mine.border;
      for (std::size_t b = 0; b < e.radial.size(); ++b) e.radial[b] += mine.radial[b];
    }
  }
  return e;
}

// Power in the outer n/16 of the window (the border only is read).
double border_power(const ComplexBuffer& u, std::size_t n) {
  const std::size_t border = std::max<std::size_t>(1, n / 16);
  double sum = 0.0;
  auto add = [&](std::size_t iy, std::size_t from, std::size_t to) {
    for (std::size_t ix = from; ix < to; ++ix) sum += std::norm(u[iy * n + ix]);
  };
  for (std::size_t iy = 0; iy < n; ++iy) {
    if (iy < border || iy >= n - border) {
      add(iy, 0, n);
    } else {
      add(iy, 0, border);
      add(iy, n - border, n);
    }
  }
  return sum;
}

}  // namespace

PropagationPlan::PropagationPlan(std::size_t n, double spacing, double wavelength, double distance,
                                 PropagationMethod method, double output_spacing)
    : n_(n), spacing_(spacing), wavelength_(wavelength), distance_(distance), output_spacing_(output_spacing) {
  if (n < 8 || n % 2 != 0 || n > kMaxGridSide)
    checks::fail("field.n", static_cast<double>(n), "an even grid size from 8 to " + std::to_string(kMaxGridSide));
  checks::grid("field.n", n, sizeof(Complex), 3);  // the field, the transfer function or chirps, a copy
  checks::length("field.spacing", spacing);
  checks::length("field.wavelength", wavelength);
  checks::coordinate("distance", distance);
  checks::non_negative("output_spacing", output_spacing);
  if (output_spacing > 0.0) checks::length("output_spacing", output_spacing);
  critical_distance_ = n * spacing * spacing / wavelength;
  if (method == PropagationMethod::automatic) {
    const bool natural_as = output_spacing == 0.0 || output_spacing == spacing;
    method = (natural_as && std::abs(distance) <= critical_distance_) ? PropagationMethod::angular_spectrum
                                                                      : PropagationMethod::fresnel;
  }
  if (distance == 0.0) method = PropagationMethod::angular_spectrum;  // the identity
  method_ = method;
  const double k = 2.0 * kPi / wavelength, z = distance;

  if (method == PropagationMethod::angular_spectrum) {
    if (output_spacing != 0.0 && output_spacing != spacing)
      checks::fail("output_spacing", output_spacing,
                   "0 or the input spacing for the angular spectrum method (its output grid is the input grid)");
    output_spacing_ = spacing;
    // A1: exp(i k z sqrt(1 - lambda^2 f^2)), zero for evanescent waves and beyond the band limit
    // 1 / (lambda sqrt((2 df z)^2 + 1)) where its phase would alias on the frequency grid. The FFT
    // normalisation 1/n^2 is folded in.
    const double df = 1.0 / (n * spacing);
    const double f_limit = 1.0 / (wavelength * std::sqrt(std::pow(2.0 * df * z, 2) + 1.0));
    const Complex carrier = unit_phasor(k * z) / static_cast<double>(n * n);
    transfer_.assign(n * n, Complex{});
#pragma omp parallel for if (n >= kParallelSide)
    for (long iy = 0; iy < static_cast<long>(n); ++iy) {
      const double fy = frequency(iy, n, spacing);
      for (std::size_t ix = 0; ix < n; ++ix) {
        const double fx = frequency(ix, n, spacing);
        const double s = wavelength * wavelength * (fx * fx + fy * fy);
        if (s >= 1.0 || std::abs(fx) > f_limit || std::abs(fy) > f_limit) continue;
        // k z (sqrt(1 - s) - 1) without cancellation.
        transfer_[iy * n + ix] = carrier * unit_phasor(-k * z * s / (1.0 + std::sqrt(1.0 - s)));
      }
    }
    return;
  }

  if (!(distance > 0.0))
    checks::fail("distance", distance, "a distance > 0 for Fresnel and Fraunhofer propagation");
  const double natural = wavelength * z / (n * spacing);
  if (output_spacing_ == 0.0) output_spacing_ = natural;
  single_fft_ = std::abs(output_spacing_ / natural - 1.0) < 1e-12;
  // A5 / A7: U2(x) = exp(ikz)/(i lambda z) exp(ik x^2/2z) dx^2 DFT[U1 (exp(ik xi^2/2z) for A5)].
  if (method == PropagationMethod::fresnel) chirp_in_ = axis_chirp(n, spacing, k, z, single_fft_);
  else if (single_fft_) chirp_in_ = axis_chirp(n, spacing, 0.0, z, true);  // the centring sign only
  chirp_out_ = axis_chirp(n, output_spacing_, k, z, single_fft_);
  front_ = unit_phasor(k * z) * Complex(0.0, -1.0) * (spacing * spacing / (wavelength * z));
}

std::shared_ptr<const PropagationPlan> PropagationPlan::cached(std::size_t n, double spacing, double wavelength,
                                                              double distance, PropagationMethod method,
                                                              double output_spacing) {
  using Key = std::tuple<std::size_t, double, double, double, int, double>;
  static std::mutex mutex;
  static std::list<std::pair<Key, std::shared_ptr<const PropagationPlan>>> recent;  // most recent first
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
  auto plan = std::make_shared<const PropagationPlan>(n, spacing, wavelength, distance, method, output_spacing);
  std::lock_guard<std::mutex> lock(mutex);
  recent.emplace_front(key, plan);
  if (recent.size() > kCapacity) recent.pop_back();
  return plan;
}

Propagated PropagationPlan::execute(Field in) const {
  in.validate();
  if (in.n != n_ || in.spacing != spacing_ || in.wavelength != wavelength_)
    checks::fail("field.n", static_cast<double>(in.n), "the grid, spacing and wavelength the plan was made for");
  Propagated out;
  PropagationReport& r = out.report;
  r.method = method_;
  r.critical_distance = critical_distance_;
  ComplexBuffer& u = in.values;  // the field is ours: transform it in place

  if (method_ == PropagationMethod::angular_spectrum) {
    // Totals come from the spectrum (Parseval), so only the window borders are read in space.
    const double input_border = border_power(u, n_);
    double input_total = 0.0, output_total = 0.0, removed = 0.0;
    if (distance_ != 0.0) {
      fft2d(u, n_, FftDirection::forward);
#pragma omp parallel for reduction(+ : input_total, output_total, removed) if (n_ >= kParallelSide)
      for (long i = 0; i < static_cast<long>(n_ * n_); ++i) {
        const double p = std::norm(u[i]);
        input_total += p;
        if (transfer_[i] == Complex{}) removed += p;
        u[i] *= transfer_[i];
        output_total += std::norm(u[i]);
      }
      fft2d(u, n_, FftDirection::backward);
      const double nn = static_cast<double>(n_ * n_);
      input_total /= nn;        // sum |u|^2 = sum |U|^2 / n^2 (unnormalised FFT)
      output_total *= nn;       // the inverse FFT multiplies power by n^2
    } else {
      for (const Complex& v : u) input_total += std::norm(v);
      output_total = input_total;
    }
    r.band_limit_loss = input_total > 0.0 ? removed / (input_total * n_ * n_) : 0.0;
    r.input_edge_power = input_total > 0.0 ? input_border / input_total : 0.0;
    r.output_edge_power = output_total > 0.0 ? border_power(u, n_) / output_total : 0.0;
    out.field = Field{std::move(u), n_, spacing_, wavelength_};
    return out;
  }

  const std::vector<Complex> unit(n_, Complex{1.0, 0.0});
  const Extent before = apply_separable(u, n_, chirp_in_.empty() ? unit : chirp_in_, 1.0);
  if (single_fft_) fft2d(u, n_, FftDirection::forward);
  else u = scaled_dft2d(u, n_, n_, spacing_ * output_spacing_ / (wavelength_ * distance_));
  const Extent after = apply_separable(u, n_, chirp_out_, front_);
  out.field = Field{std::move(u), n_, output_spacing_, wavelength_};
  r.input_edge_power = before.edge_fraction();
  r.output_edge_power = after.edge_fraction();
  r.scaled_output = !single_fft_;
  // Extents about the optical axis, where A3 and A6 measure them.
  const double a_in = before.radius(kSupportFraction, spacing_);
  const double a_out = after.radius(kSupportFraction, output_spacing_);
  const double k = 2.0 * kPi / wavelength_;
  r.chirp_phase_step = method_ == PropagationMethod::fresnel ? k * a_in * spacing_ / distance_ : 0.0;
  r.fresnel_phase_error = kPi / (4.0 * wavelength_) * std::pow(a_in + a_out, 4) / std::pow(distance_, 3);
  r.fraunhofer_phase = kPi * a_in * a_in / (wavelength_ * distance_);
  return out;
}

Propagated propagate(Field in, double distance, PropagationMethod method, double output_spacing) {
  const auto plan = PropagationPlan::cached(in.n, in.spacing, in.wavelength, distance, method, output_spacing);
  Propagated out = plan->execute(std::move(in));
  for (const Complex& v : out.field.values)
    if (!std::isfinite(v.real()) || !std::isfinite(v.imag()))
      throw std::domain_error("propagate: the field holds non-finite values after " + checks::number(distance) +
                              " m: its input was not finite, or the distance and sampling leave double precision");
  return out;
}

}  // namespace lidar_overlap
