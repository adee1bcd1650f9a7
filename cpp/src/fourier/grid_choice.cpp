#include "lidar_overlap/fourier/grid_choice.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "lidar_overlap/core/limits.hpp"
#include "core/cancel_every.hpp"
#include "core/checks.hpp"
#include "fourier/fft.hpp"
#include "fourier/zeroed_buffer.hpp"

namespace lidar_overlap {

namespace {

// All but this fraction of the power lies inside the radii that size the grid (the validity checks
// flag 1e-6 of the power in the window's outer n/16).
constexpr double kOutsideFraction = 1e-7;

// Radius, in samples from the grid centre (index n/2), holding all but kOutsideFraction of sum |u|^2.
// With `fft_order` the grid is an FFT output, whose centre is index 0 (wrapped).
double power_radius(const ComplexBuffer& u, std::size_t n, bool fft_order) {
  // Bins of one sample^2 in r^2 up to the corner, n^2 / 2.
  std::vector<double> bins(n * n / 2 + 2, 0.0);
  double total = 0.0;
  auto offset = [&](std::size_t i) {
    const long k =
        fft_order ? (i < n / 2 ? static_cast<long>(i) : static_cast<long>(i) - static_cast<long>(n))
                  : static_cast<long>(i) - static_cast<long>(n / 2);
    return static_cast<double>(k);
  };
  for (std::size_t iy = 0; iy < n; ++iy) {
    detail::cancellation_point();  // once per row of a grid of up to 16384^2
    const double y = offset(iy);
    for (std::size_t ix = 0; ix < n; ++ix) {
      const double x = offset(ix), p = std::norm(u[iy * n + ix]);
      bins[std::min(bins.size() - 1, static_cast<std::size_t>(x * x + y * y))] += p;
      total += p;
    }
  }
  double outside = 0.0;
  for (std::size_t b = bins.size(); b-- > 0;) {
    outside += bins[b];
    if (outside > kOutsideFraction * total) return std::sqrt(static_cast<double>(b + 1));
  }
  return 0.0;
}

}  // namespace

GridChoice choose_grid(const Field& in, double distance, PropagationMethod method,
                       std::size_t max_n) {
  in.validate();
  checks::coordinate("distance", distance);
  const std::size_t n = in.n;
  const double dx = in.spacing, lambda = in.wavelength, z = std::abs(distance);
  ComplexBuffer spectrum = in.values;
  fft2d(spectrum, n, FftDirection::forward);

  GridChoice g{n, method, 0.0, 0.0, 0.0};
  g.input_radius = dx * power_radius(in.values, n, false);
  g.angular_radius = std::min(1.0, lambda * power_radius(spectrum, n, true) / (n * dx));
  // Rays from inside the input radius at angles inside the angular radius stay inside this one.
  g.output_radius = g.input_radius + z * g.angular_radius;

  // Angular spectrum: the output (on the input spacing) inside 7/16 of the window, and the band limit
  // 1 / (lambda sqrt((2 z / (n dx))^2 + 1)) above the spectrum's extent.
  double n_as = 16.0 * g.output_radius / (7.0 * dx);
  const double sin_max = g.angular_radius;
  if (sin_max > 0.0 && sin_max < 1.0)
    n_as = std::max(n_as, 2.0 * z / (dx * std::sqrt(1.0 / (sin_max * sin_max) - 1.0)));
  const std::size_t n_as_fast =
      next_power_of_two(std::max<std::size_t>(n, checks::saturate(std::ceil(n_as))));
  // Fresnel and Fraunhofer: the output window lambda z / dx does not depend on n. The output irradiance
  // is |FT(input x chirp)|^2, band-limited to the input's diameter over lambda z, so the output spacing
  // lambda z / (n dx) samples it at Nyquist once the window n dx spans twice that diameter.
  const double n_fr = 4.0 * g.input_radius / dx;
  const std::size_t n_fr_fast =
      next_power_of_two(std::max<std::size_t>(n, checks::saturate(std::ceil(n_fr))));

  // Powers of two: FFTW's fastest sizes, and few of them, so that plans are made once and reused across
  // calls (planning a new size costs far more than one transform).
  if (method == PropagationMethod::automatic)
    // auto: the angular spectrum while the padded grid's critical distance reaches z, as in PropagationPlan.
    g.method = z <= n_as_fast * dx * dx / lambda ? PropagationMethod::angular_spectrum
                                                 : PropagationMethod::fresnel;
  g.n = g.method == PropagationMethod::angular_spectrum ? n_as_fast : n_fr_fast;
  if (distance == 0.0) g.n = n;
  if (g.n > max_n)
    checks::fail("grid_size", static_cast<double>(g.n),
                 "at most " + std::to_string(max_n) +
                     " samples per side: the field spreads to a radius of " +
                     std::to_string(g.output_radius) +
                     " m at this distance; sample it more coarsely or use "
                     "method 'fresnel', whose output grid grows with distance");
  return g;
}

Field zero_pad(const Field& in, std::size_t n) {
  in.validate();
  if (n < in.n || n % 2)
    checks::fail("grid_size", static_cast<double>(n),
                 "an even size >= the field's " + std::to_string(in.n));
  checks::grid("grid_size", n, sizeof(Complex),
               3);  // the padded field, the plan's transfer function, a copy
  Field out{detail::zeroed_buffer(n * n), n, in.spacing, in.wavelength};
  const std::size_t off = n / 2 - in.n / 2;  // keeps index n/2 at x = 0
  for (std::size_t iy = 0; iy < in.n; ++iy)
    std::copy(in.values.begin() + iy * in.n, in.values.begin() + (iy + 1) * in.n,
              out.values.begin() + (iy + off) * n + off);
  return out;
}

}  // namespace lidar_overlap
