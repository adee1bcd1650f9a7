// The padded spectrum of the 2-D Fourier-optics overlap (overlap_fo_detail.hpp): its size, which must hold the
// aliases' period on the detector plane, and the phases that place the beam image against the detector.
#include "fourier/overlap_fo_detail.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/checks.hpp"
#include "core/constants.hpp"
#include "core/entry_checks.hpp"
#include "fourier/fft.hpp"

namespace lidar_overlap::detail {

std::size_t even_fast_fft_size(std::size_t n) {
  std::size_t m = fast_fft_size(n);
  while (m % 2) m = fast_fft_size(m + 1);
  return m;
}

ShiftPhases::ShiftPhases(std::size_t np, double df, Vec2 shift) : x(np), y(np) {
  for (std::size_t k = 0; k < np; ++k) {
    const double sign = (k % 2) ? -1.0 : 1.0,
                 f = df * (k < np / 2 ? static_cast<double>(k) : static_cast<double>(k) - np);
    x[k] = sign * std::polar(1.0, 2.0 * kPi * f * shift.x);
    y[k] = sign * std::polar(1.0, 2.0 * kPi * f * shift.y);
  }
}

std::size_t spectrum_grid(const LidarSystem& system, const FoReceiver& rx, double z, double spacing,
                          double radius_bound, std::size_t n, std::size_t max_grid,
                          std::size_t range_index, double tail_error, bool any_fast_size) {
  // The frequency spacing 1/(n dx) sets the period (on the detector plane) of the sum's aliases: it
  // must exceed the reach of the point image plus that of the beam image and the detector. Twice the
  // 1e-7 power radius (5.7 w for TEM00) leaves the beam's tails beyond it below 1e-30 of its power.
  if (!rx.passes_light()) return 0;  // G = 0: no grid
  const double to_image = rx.detector_distance() / z;
  const double reach = rx.blur_radius() + 20.0 / rx.cutoff() +
                       norm(system.detector.offset + to_image * system.beam.center(z)) +
                       system.detector.radius + 2.0 * radius_bound * to_image;
  // The aliases also sit in the far diffraction tails of each other's point images: their period must
  // keep those below tail_error of G (1e-6: 4e-7 measured against a direct quadrature).
  const double period = 1.1 * reach + rx.tail_period(tail_error);
  const std::size_t least =
      std::max<std::size_t>(n, checks::saturate(std::ceil(period / (spacing * to_image))));
  const std::size_t np =
      any_fast_size && least <= max_grid ? even_fast_fft_size(least) : next_power_of_two(least);
  if (np > max_grid)
    checks::fail(
        detail::range_name(range_index), z,
        "a range needing a beam spectrum grid of at most max_spectrum_grid = " +
            std::to_string(max_grid) + " (here " + std::to_string(np) +
            "): its alias period must hold, on the detector plane, the "
            "point image (blur radius " +
            checks::number(rx.blur_radius()) + " m), the beam image (offset " +
            checks::number(norm(system.detector.offset + to_image * system.beam.center(z))) +
            " m, radius " + checks::number(radius_bound * to_image) + " m) and the detector (" +
            checks::number(system.detector.radius) +
            " m); where the blur dominates the image is geometric and "
            "method 'rt' is exact, otherwise fo_path='radial' needs no grid");
  return np;
}

}  // namespace lidar_overlap::detail
