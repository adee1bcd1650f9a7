#include "lidar_overlap/pupil/overlap_fo_aberrated.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "lidar_overlap/fourier/overlap_fo.hpp"
#include "lidar_overlap/fourier/overlap_fo_radial.hpp"
#include "core/checks.hpp"
#include "core/constants.hpp"
#include "core/entry_checks.hpp"
#include "core/parallel.hpp"
#include "fourier/fft.hpp"
#include "fourier/fo_receiver.hpp"
#include "fourier/gaussian_image_overlap.hpp"
#include "fourier/otf.hpp"
#include "fourier/overlap_fo_detail.hpp"
#include "pupil/sampled_pupil_overlap.hpp"

namespace lidar_overlap {

namespace {

// The beam image's spectrum exp(-pi^2 w^2 q^2 / 2) is below 4e-14 beyond |q| = 2.5 / w.
constexpr double kImageSpectrumReach = 2.5;

// Writes P(a) exp(i psi |a|^2 + 2 pi i W(a / R) / lambda) into the centre of an n x n buffer at pupil spacing
// `delta` (m). Edge pixels carry the annulus area they hold (8 x 8 sub-samples), so the sampled pupil keeps
// the continuous one's area and low-frequency content.
// With a mask (sectors, empty: none) the pupil is cut to it; pixels its boundary crosses are sub-sampled too.
void sample_pupil(const FoReceiver& rx, const Aberrations& aberrations, const PupilPolynomial& poly,
                  double telescope_radius, double wavelength, double delta, std::size_t n,
                  const std::vector<AnnularSector>& mask, ComplexBuffer& out) {
  auto in_mask = [&](Vec2 a) {
    if (mask.empty()) return true;
    for (const AnnularSector& s : mask)
      if (sector_contains(s, a)) return true;
    return false;
  };
  auto near_mask_edge = [&](Vec2 a, double reach) {
    for (const AnnularSector& s : mask)
      if (sector_boundary_distance(s, a) < reach) return true;
    return false;
  };
  out.assign(n * n, Complex{});
  const AnnularPupil& pupil = rx.pupil();
  const double k = 2.0 * kPi / wavelength, half_diagonal = 0.7072 * delta;
  const long half = static_cast<long>(std::ceil(pupil.outer / delta)) + 1,
             centre = static_cast<long>(n / 2);
  std::vector<double> row(std::max(poly.degree, 0) + 1);
  for (long iy = -half; iy <= half; ++iy) {
    const double y = iy * delta;
    if (poly.degree >= 0) poly.row(y / telescope_radius, row.data());
    for (long ix = -half; ix <= half; ++ix) {
      const double x = ix * delta, r = std::hypot(x, y);
      double area = 1.0;
      if (r - half_diagonal >= pupil.outer || r + half_diagonal <= pupil.inner) continue;
      const bool mask_edge = near_mask_edge({x, y}, half_diagonal);
      if (!mask_edge && !in_mask({x, y})) continue;
      if (mask_edge || r + half_diagonal > pupil.outer || r - half_diagonal < pupil.inner) {
        int inside = 0;
        for (int sy = 0; sy < 8; ++sy)
          for (int sx = 0; sx < 8; ++sx) {
            const Vec2 a{x + (sx - 3.5) / 8.0 * delta, y + (sy - 3.5) / 8.0 * delta};
            const double rs =
                std::hypot(a.x, a.y);  // as before masks: the same pixels for every pupil
            inside += rs < pupil.outer && rs >= pupil.inner && (!mask_edge || in_mask(a));
          }
        area = inside / 64.0;
        if (area == 0.0) continue;
      }
      double w;
      if (poly.degree >= 0) {
        const double px = x / telescope_radius;
        w = 0.0;
        for (int p = poly.degree; p >= 0; --p) w = w * px + row[p];
      } else {
        w = aberrations.wavefront({x / telescope_radius, y / telescope_radius});
      }
      out[(iy + centre) * n + ix + centre] = std::polar(area, pupil.psi * r * r + k * w);
    }
  }
}

struct RangePlan {
  std::size_t n = 0;   // transform size
  double delta = 0.0;  // m, pupil spacing
  long lags = 0;       // pupil shifts (in samples) where the beam image's spectrum is above 4e-14
};

// Sampling at range z (see the header): the alias period L = lambda d / delta holds the point image and the
// beam image on the detector apart from their copies; the transform holds the pupil plus the largest lag
// without wrapping the autocorrelation.
RangePlan plan_range(const LidarSystem& system, const FoReceiver& rx, double blur, double z,
                     const FoAberratedOptions& options, std::size_t index) {
  if (!rx.passes_light()) return {};  // G = 0: no transform
  const double d = rx.detector_distance(), to_image = d / z, lambda = system.beam.wavelength;
  const double w = system.beam.radius(z) * to_image;
  const double s0 = norm((-to_image) * system.beam.center(z) - system.detector.offset);
  const double reach = blur + 20.0 / rx.cutoff() + s0 + system.detector.radius + 3.0 * w;
  const double period = 1.1 * reach + rx.tail_period(options.tail_error);
  RangePlan p;
  p.delta = lambda * d / period;
  // Sizes in floating point first: with huge blurs they exceed any grid long before they are rounded.
  const double lags = std::ceil(kImageSpectrumReach * period / w) + 1.0;
  const double needed = 2.0 * std::ceil(rx.pupil().outer / p.delta) + 4.0 + lags;
  p.lags = static_cast<long>(std::min(lags, 1e9));
  p.n = needed <= static_cast<double>(options.max_grid)
            ? fast_fft_size(static_cast<std::size_t>(needed))
            : checks::saturate(needed);
  if (p.n > options.max_grid)
    checks::fail(
        detail::range_name(index), z,
        "a range whose point image (blur radius " + std::to_string(blur) +
            " m on the detector plane) fits a pupil transform of at most max_grid = " +
            std::to_string(options.max_grid) + " (here " + std::to_string(p.n) +
            "); the defocus blur is geometric there, where method 'rt' traces the aberrations exactly");
  return p;
}

double telescope_radius(const LidarSystem& system) { return 0.5 * system.telescope.diameter; }

}  // namespace

FoAberratedOverlap overlap_fo_aberrated(const LidarSystem& system, const Aberrations& aberrations,
                                        const std::vector<double>& ranges,
                                        const FoAberratedOptions& options) {
  system.validate();
  aberrations.validate();
  if (aberrations.field_dependent())
    throw std::invalid_argument(
        "aberrations with W131, W222, W220 or W311 vary across the field, which the Fourier-"
        "optics path (one point image for every scatterer) cannot model: use method 'rt', "
        "or their Zernike form at one field point");
  return detail::overlap_fo_sampled(system, aberrations, {}, ranges, options,
                                    "overlap_fo_aberrated");
}

namespace detail {

FoAberratedOverlap overlap_fo_sampled(const LidarSystem& system, const Aberrations& aberrations,
                                      const std::vector<AnnularSector>& mask,
                                      const std::vector<double>& ranges,
                                      const FoAberratedOptions& options, const std::string& name) {
  system.validate();
  system.beam.validate_for_fourier_optics();
  if (aberrations.pupil_polynomial().degree < 0)
    checks::fail(
        "aberrations.zernike (highest Noll index)", static_cast<double>(aberrations.zernike.size()),
        "at most 153 (radial order 16) for Fourier optics, which samples the pupil as one polynomial "
        "(higher orders lose digits to cancellation and cost O(order) per sample): use method 'rt'");
  const int threads = detail::checked_threads_and_ranges(system, ranges, options.threads);
  checks::in_open_unit("tail_error", options.tail_error);
  const double radius = telescope_radius(system);
  const double ray_blur = aberrations.max_gradient() / radius;  // rad: d grad W / R per unit d
  std::vector<FoReceiver> receivers;
  std::vector<RangePlan> plans;
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    receivers.emplace_back(system, ranges[i], detail::range_name(i));
    const FoReceiver& rx = receivers.back();
    const double blur = rx.blur_radius() + rx.detector_distance() * ray_blur;
    plans.push_back(plan_range(system, rx, blur, ranges[i], options, i));
  }
  const PupilPolynomial poly = aberrations.pupil_polynomial();
  FoAberratedOverlap out;
  out.overlap.assign(ranges.size(), 0.0);
  for (const RangePlan& p : plans) out.grid.push_back(p.n);
  detail::parallel_for(ranges.size(), threads, [&](std::size_t i) {
    const FoReceiver& rx = receivers[i];
    if (!rx.passes_light()) return;
    const RangePlan& p = plans[i];
    const double z = ranges[i], d = rx.detector_distance(), to_image = d / z;
    const double w = system.beam.radius(z) * to_image, r_d = system.detector.radius;
    const Vec2 s0 = (-to_image) * system.beam.center(z) - system.detector.offset;
    // Autocorrelations of the sampled pupil with and without the aberrations (the OTF at pupil shifts
    // m delta), two transforms each. Their difference carries the aberrations; the sampling's own errors (edge
    // pixels, the aliases' tails) are nearly the same in both and cancel, and the aberration-free G is exact.
    ComplexBuffer aberrated, plain;
    sample_pupil(rx, aberrations, poly, radius, system.beam.wavelength, p.delta, p.n, mask,
                 aberrated);
    sample_pupil(rx, Aberrations{}, Aberrations{}.pupil_polynomial(), radius,
                 system.beam.wavelength, p.delta, p.n, {}, plain);
    for (ComplexBuffer* b : {&aberrated, &plain}) {
      fft2d(*b, p.n, FftDirection::forward, FftPlanning::estimate);
      for (Complex& v : *b) v = std::norm(v);
      fft2d(*b, p.n, FftDirection::backward, FftPlanning::estimate);
    }
    // G = sum_m OTF(q_m) K^(q_m) exp(-2 pi i q_m . s0) dq^2 / (pi R^2), q_m = m delta / (lambda d), with
    // K^ = exp(-pi^2 w^2 q^2 / 2) disc^(q) the spectrum of the beam image seen through the detector.
    const long n = static_cast<long>(p.n);
    const double dq = p.delta / (system.beam.wavelength * d), q_max = kImageSpectrumReach / w;
    std::vector<Complex> phase_x(2 * p.lags + 1), phase_y(2 * p.lags + 1);
    for (long m = -p.lags; m <= p.lags; ++m) {
      phase_x[m + p.lags] = std::polar(1.0, -2.0 * kPi * m * dq * s0.x);
      phase_y[m + p.lags] = std::polar(1.0, -2.0 * kPi * m * dq * s0.y);
    }
    double sum = 0.0;
    for (long my = -p.lags; my <= p.lags; ++my) {
      const std::size_t row = static_cast<std::size_t>((my + n) % n) * p.n;
      for (long mx = -p.lags; mx <= p.lags; ++mx) {
        const double q = dq * std::hypot(static_cast<double>(mx), static_cast<double>(my));
        if (q >= q_max) continue;
        const std::size_t at = row + static_cast<std::size_t>((mx + n) % n);
        const Complex r = aberrated[at] - plain[at];  // R_m = sum_j P_{j+m} conj(P_j), difference
        const double k_hat = std::exp(-0.5 * kPi * kPi * w * w * q * q) * disc_transform(r_d, q);
        sum += k_hat * (std::conj(r) * phase_x[mx + p.lags] * phase_y[my + p.lags]).real();
      }
    }
    const double n2 = static_cast<double>(p.n) * static_cast<double>(p.n);
    out.overlap[i] = gaussian_image_overlap(system, z, 4.0, nullptr, detail::range_name(i)) +
                     sum * p.delta * p.delta * dq * dq / (n2 * kPi * radius * radius);
  });
  checks::overlap_values(out.overlap, ranges, detail::kFoOverlapSlack, name);
  return out;
}

}  // namespace detail

Field point_image(const LidarSystem& system, const Aberrations& aberrations, double z,
                  std::size_t n, double spacing) {
  system.validate();
  aberrations.validate();
  if (aberrations.field_dependent())
    throw std::invalid_argument(
        "point_image takes field-independent aberrations (Zernike terms and W040)");
  if (n < 8 || n % 2) checks::fail("n", static_cast<double>(n), "an even size >= 8");
  checks::grid("n", n, sizeof(Complex), 3);  // the pupil, the image and the caller's copy
  checks::length("spacing", spacing);
  const FoReceiver rx(system, z);
  const double lambda = system.beam.wavelength, d = rx.detector_distance();
  const double delta = lambda * d / (n * spacing), radius = telescope_radius(system);
  if (2 * (static_cast<std::size_t>(std::ceil(rx.pupil().outer / delta)) + 2) > n)
    checks::fail("spacing", spacing,
                 "at most lambda d / D (1 - 8/n) = " +
                     std::to_string(lambda * d / (2.0 * rx.pupil().outer) * (1.0 - 8.0 / n)) +
                     " m, so that the pupil fits the n x n transform");
  ComplexBuffer buffer;
  sample_pupil(rx, aberrations, aberrations.pupil_polynomial(), radius, lambda, delta, n, {},
               buffer);
  fft2d(buffer, n, FftDirection::forward);  // a size users call again: FFTW_MEASURE pays off
  Field f;
  f.n = n;
  f.spacing = spacing;
  f.wavelength = lambda;
  f.values.assign(n * n, Complex{});
  // Centred output (index n/2 is 0); the pupil's centring phase (-1)^(kx + ky) removed.
  const double scale = delta / (n * std::sqrt(kPi) * radius * spacing);
  for (std::size_t ky = 0; ky < n; ++ky)
    for (std::size_t kx = 0; kx < n; ++kx) {
      const double sign = ((kx + ky) % 2) ? -scale : scale;
      f.values[((ky + n / 2) % n) * n + (kx + n / 2) % n] = sign * buffer[ky * n + kx];
    }
  return f;
}

}  // namespace lidar_overlap
