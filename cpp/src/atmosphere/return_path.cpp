#include "atmosphere/return_path.hpp"

#include <cmath>
#include <random>

#include "lidar_overlap/atmosphere/turbulent_grid.hpp"
#include "core/checks.hpp"
#include "core/constants.hpp"
#include "core/parallel.hpp"
#include "fourier/fft_passes.hpp"

namespace lidar_overlap::detail {

namespace {

// splitmix64's mixer (as the phase screens use it): unrelated generator states for nearby (seed, k, m).
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

constexpr int kSub = 4;  // sub-samples per axis for the share of a detector sample inside the disc

}  // namespace

ReturnPath::ReturnPath(const LidarSystem& system, std::size_t n, double spacing, std::size_t fields)
    : system_(system),
      n_(n),
      fields_(fields),
      spacing_(spacing),
      lambda_(system.beam.wavelength),
      d_(system.telescope.focal_length + system.detector.defocus),
      area_(0.25 * kPi * system.telescope.diameter * system.telescope.diameter) {
  const Vec2 c = system.detector.offset;
  const double r = system.detector.radius;
  // The pupil's samples must resolve the plane waves of the detector's edge: (|offset| + r) / d below
  // lambda / (2 spacing), with the margin of one detector sample.
  if ((norm(c) + r) / d_ >= lambda_ / (2.0 * spacing) * (1.0 - 1.0 / kSamples))
    checks::fail(
        "beam_grid", static_cast<double>(n),
        "a grid whose pupil spacing resolves the field of view (detector radius plus offset over the detector "
        "distance below lambda / (2 spacing)): raise beam_grid");
  // kSamples per radius, finer than any feature of the pupil field the grid can hold; each with the share of
  // its cell inside the disc (kSub x kSub points).
  step_ = r / kSamples;
  const int m = kSamples + 1;
  for (int iy = -m; iy <= m; ++iy)
    for (int ix = -m; ix <= m; ++ix) {
      int inside = 0;
      for (int b = 0; b < kSub; ++b)
        for (int a = 0; a < kSub; ++a) {
          const double sx = (ix + (a + 0.5) / kSub - 0.5) * step_,
                       sy = (iy + (b + 0.5) / kSub - 0.5) * step_;
          inside += sx * sx + sy * sy <= r * r;
        }
      if (inside) {
        detector_.push_back({c.x + ix * step_, c.y + iy * step_});
        detector_weight_.push_back(std::sqrt(static_cast<double>(inside) / (kSub * kSub)));
      }
    }
  // exp(-i 2 pi a x / (lambda d)) per pupil coordinate a (the grid's, plus the beam's offset: the aperture's
  // frame) and detector column / row: the direct transform, separable.
  const double h = 0.5 * static_cast<double>(n), w = -2.0 * kPi / (lambda_ * d_);
  for (int j = -m; j <= m; ++j) {
    const double xj = c.x + j * step_, yj = c.y + j * step_;
    for (std::size_t i = 0; i < n; ++i) {
      const double g = (static_cast<double>(i) - h) * spacing;
      kernel_x_.push_back(std::polar(1.0, w * (g + system.beam.offset.x) * xj));
      kernel_y_.push_back(std::polar(1.0, w * (g + system.beam.offset.y) * yj));
    }
  }
}

double ReturnPath::max_angle() const { return receiver_max_angle(system_); }

double ReturnPath::footprint(double z) const {
  const Telescope& t = system_.telescope;
  return std::abs(0.5 * t.diameter * (1.0 - z * (1.0 / t.focal_length - 1.0 / d_))) +
         (system_.detector.radius + norm(system_.detector.offset)) * z / d_;
}

Field ReturnPath::pupil_field(std::uint64_t seed, std::size_t k, std::size_t m) const {
  const std::size_t n = n_, h = n / 2;
  const int side = 2 * (kSamples + 1) + 1;
  std::mt19937_64 rng(
      mix(mix(mix(seed) ^ static_cast<std::uint64_t>(k)) ^ static_cast<std::uint64_t>(m)));
  // The detector's samples with independent uniform phases, as a side x side block (zero outside the disc).
  std::vector<Complex> block(static_cast<std::size_t>(side * side), Complex{});
  for (std::size_t s = 0; s < detector_.size(); ++s) {
    const int jx =
        static_cast<int>(std::lround((detector_[s].x - system_.detector.offset.x) / step_)) +
        kSamples + 1;
    const int jy =
        static_cast<int>(std::lround((detector_[s].y - system_.detector.offset.y) / step_)) +
        kSamples + 1;
    block[static_cast<std::size_t>(jy * side + jx)] =
        std::polar(detector_weight_[s], 2.0 * kPi * static_cast<double>(rng() >> 11) * 0x1p-53);
  }
  // Along x for every detector row, then along y: V(a) = step / (lambda d) sum_x D(x) exp(-i 2 pi a x / (lambda d)),
  // a delta-correlated detector field's transform (a unit sample stands for step^2 of it).
  std::vector<Complex> rows(static_cast<std::size_t>(side) * n, Complex{});
  for (int jy = 0; jy < side; ++jy)
    for (int jx = 0; jx < side; ++jx) {
      const Complex v = block[static_cast<std::size_t>(jy * side + jx)];
      if (v == Complex{}) continue;
      const Complex* kx = &kernel_x_[static_cast<std::size_t>(jx) * n];
      Complex* row = &rows[static_cast<std::size_t>(jy) * n];
      for (std::size_t i = 0; i < n; ++i) row[i] += v * kx[i];
    }
  const Telescope& t = system_.telescope;
  const double k_wave = 2.0 * kPi / lambda_,
               curvature = 0.5 * k_wave * (1.0 / d_ - 1.0 / t.focal_length);
  const double outer = 0.5 * t.diameter, inner = t.obstruction_radius,
               scale = step_ / (lambda_ * d_);
  const Vec2 offset = system_.beam.offset, tilt = system_.beam.tilt;
  Field f{ComplexBuffer(n * n, Complex{}), n, spacing_, lambda_};
  ComplexBuffer v(
      n);  // one pupil row's sums, accumulated a detector row at a time (contiguous, vectorised)
  for (std::size_t iy = 0; iy < n; ++iy) {
    detail::
        cancellation_point();  // n^2 sums over the detector's rows, for each of up to 1000 fields
    const double gy = (static_cast<double>(iy) - static_cast<double>(h)) * spacing_,
                 ay = gy + offset.y;
    if (ay * ay > outer * outer) continue;  // the row misses the aperture
    std::fill(v.begin(), v.end(), Complex{});
    for (std::size_t jy = 0; jy < static_cast<std::size_t>(side); ++jy) {
      const Complex k = kernel_y_[jy * n + iy];
      const Complex* row = &rows[jy * n];
      for (std::size_t ix = 0; ix < n; ++ix) v[ix] += detail::product(k, row[ix]);
    }
    for (std::size_t ix = 0; ix < n; ++ix) {
      const double gx = (static_cast<double>(ix) - static_cast<double>(h)) * spacing_;
      const double ax = gx + offset.x, r2 = ax * ax + ay * ay;
      if (r2 > outer * outer || r2 < inner * inner) continue;
      // The defocus's curvature (focus at the conjugate range) and, on a tilted beam's drifting grid, the
      // opposite tilt.
      f.values[iy * n + ix] =
          v[ix] * std::polar(scale, curvature * r2 - k_wave * (tilt.x * gx + tilt.y * gy));
    }
  }
  return f;
}

}  // namespace lidar_overlap::detail
