#include "lidar_overlap/overlap_turbulent.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "lidar_overlap/checks.hpp"
#include "lidar_overlap/constants.hpp"
#include "lidar_overlap/overlap_fo.hpp"
#include "lidar_overlap/phase_screen.hpp"
#include "lidar_overlap/fft.hpp"
#include "overlap_fo_detail.hpp"

namespace lidar_overlap {

namespace {

// A plane the beam passes: a phase screen or a range where the overlap is wanted.
struct Plane {
  double z;
  int screen = -1;  // index into the screens, or -1
  int range = -1;   // index into the ranges, or -1
};

// One split step of the scaled angular-spectrum (Fresnel transfer function) method: n x n samples of
// spacing d1 at one plane to spacing d2 = m d1 at a plane dz further, with m chosen to follow the beam's
// growth, U2 = Q3 IFFT[Q2 FFT(Q1 U1 / m)] with Q1 = exp(i k (1 - m) r1^2 / (2 dz)), Q2 = exp(-i 2 pi^2 dz
// f^2 / (m k)), Q3 = exp(i k (m - 1) r2^2 / (2 m dz)) (J. D. Schmidt, Numerical Simulation of Optical Wave
// Propagation, 2010, Sec. 8.2). All three are separable in x and y.
class ScaledStep {
 public:
  ScaledStep(std::size_t n, double d1, double d2, double dz, double lambda) : n_(n), d2_(d2) {
    const double k = 2.0 * kPi / lambda, m = d2 / d1;
    q1_.resize(n), q2_.resize(n), q3_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double x1 = (static_cast<double>(i) - 0.5 * n) * d1, x2 = (static_cast<double>(i) - 0.5 * n) * d2;
      const double f = (i < n / 2 ? static_cast<double>(i) : static_cast<double>(i) - static_cast<double>(n)) / (n * d1);
      q1_[i] = std::polar(1.0, k * (1.0 - m) * x1 * x1 / (2.0 * dz));
      q2_[i] = std::polar(1.0, -2.0 * kPi * kPi * dz * f * f / (m * k));
      q3_[i] = std::polar(1.0, k * (m - 1.0) * x2 * x2 / (2.0 * m * dz));
    }
    scale_in_ = 1.0 / m;
    scale_out_ = 1.0 / (static_cast<double>(n) * n);
  }
  void execute(Field& u) const {
    const std::size_t n = n_;
    for (std::size_t iy = 0; iy < n; ++iy)
      for (std::size_t ix = 0; ix < n; ++ix) u.values[iy * n + ix] *= q1_[iy] * q1_[ix] * scale_in_;
    fft2d(u.values, n, FftDirection::forward);
    for (std::size_t iy = 0; iy < n; ++iy)
      for (std::size_t ix = 0; ix < n; ++ix) u.values[iy * n + ix] *= q2_[iy] * q2_[ix];
    fft2d(u.values, n, FftDirection::backward);
    for (std::size_t iy = 0; iy < n; ++iy)
      for (std::size_t ix = 0; ix < n; ++ix) u.values[iy * n + ix] *= q3_[iy] * q3_[ix] * scale_out_;
    u.spacing = d2_;
  }

 private:
  std::size_t n_;
  double d2_, scale_in_ = 1.0, scale_out_ = 1.0;
  std::vector<Complex> q1_, q2_, q3_;
};

}  // namespace

TurbulentOverlap overlap_fo_turbulent(const LidarSystem& system, const std::vector<double>& ranges,
                                      const Cn2Profile& atmosphere, const TurbulenceOptions& o) {
  system.validate();
  atmosphere.validate();
  const GaussianBeam& beam = system.beam;
  const double lambda = beam.wavelength, w0 = beam.waist_radius;
  if (beam.width_law != WidthLaw::gaussian ||
      (beam.divergence && std::abs(*beam.divergence * kPi * w0 / lambda - 1.0) > 1e-9))
    checks::fail("beam.divergence", beam.divergence.value_or(0.0),
                 "None (a diffraction-limited TEM00 beam with the Gaussian width law) for the turbulent FO path");
  if (o.realizations < 1) checks::fail("realizations", 0.0, "at least 1");
  if (o.screens < 1) checks::fail("screens", 0.0, "at least 1");
  if (o.beam_grid < 32 || o.beam_grid % 2) checks::fail("beam_grid", static_cast<double>(o.beam_grid), "an even size >= 32");
  checks::positive("beam_window", o.beam_window);
  if (o.threads < 0) checks::fail("threads", o.threads, "0 (all cores) or a count >= 1");
  if (ranges.empty()) return {};
  for (std::size_t i = 0; i < ranges.size(); ++i) system.validate_range(ranges[i], "ranges[" + std::to_string(i) + "]");
  const double z_max = *std::max_element(ranges.begin(), ranges.end());
  const std::size_t n = o.beam_grid;

  // Each plane's grid spans beam_window long-term radii plus 8 rms wander: the beam of any realisation
  // stays inside it (all but ~1e-9 of its power at 8 W_LT); the transmitter plane samples the waist alike.
  auto spacing_at = [&](double z) {
    if (z == 0.0) return o.beam_window * w0 / n;
    const double wander = std::sqrt(atmosphere.beam_wander_variance(w0, lambda, z));
    return (o.beam_window * atmosphere.long_term_radius(w0, lambda, z) + 8.0 * wander) / n;
  };
  const std::vector<ScreenPlacement> placements = atmosphere.place_screens(lambda, z_max, o.screens);
  std::vector<Plane> planes;
  for (std::size_t j = 0; j < placements.size(); ++j) planes.push_back({placements[j].range, static_cast<int>(j), -1});
  for (std::size_t i = 0; i < ranges.size(); ++i) planes.push_back({ranges[i], -1, static_cast<int>(i)});
  std::stable_sort(planes.begin(), planes.end(), [](const Plane& a, const Plane& b) { return a.z < b.z; });

  // Shared, made once: one screen generator and one scaled split step per plane (the grid spacing grows
  // with the beam), the receivers and spectrum grids per range.
  std::vector<std::unique_ptr<PhaseScreenGenerator>> generators(placements.size());
  std::vector<std::unique_ptr<ScaledStep>> steps;
  std::vector<double> range_spacing(ranges.size());
  std::vector<FoReceiver> receivers;
  std::vector<std::size_t> grids(ranges.size());
  double z_prev = 0.0, dx_prev = spacing_at(0.0);
  for (const Plane& p : planes) {
    const double dx = std::max(dx_prev, spacing_at(p.z));
    steps.push_back(p.z > z_prev ? std::make_unique<ScaledStep>(n, dx_prev, dx, p.z - z_prev, lambda) : nullptr);
    if (p.screen >= 0)
      generators[p.screen] = std::make_unique<PhaseScreenGenerator>(n, dx, placements[p.screen].r0, atmosphere.outer_scale,
                                                                    atmosphere.inner_scale);
    if (p.range >= 0) range_spacing[p.range] = dx;
    z_prev = p.z;
    dx_prev = dx;
  }
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    receivers.emplace_back(system, ranges[i]);
    const double radius = 2.84 * (atmosphere.long_term_radius(w0, lambda, ranges[i]) +
                                  3.0 * std::sqrt(atmosphere.beam_wander_variance(w0, lambda, ranges[i])));
    // Tails to 1e-4 of G: far below the spread between realisations, at a quarter of the grid of 1e-6.
    grids[i] = detail::spectrum_grid(system, receivers[i], ranges[i], range_spacing[i], radius, n,
                                     o.max_spectrum_grid, i, 1e-4);
  }

  TurbulentOverlap out;
  out.overlap.assign(o.realizations, std::vector<double>(ranges.size(), 0.0));
  out.wander_x.assign(o.realizations, 0.0);
  out.wander_y.assign(o.realizations, 0.0);
  out.radius_last.assign(o.realizations, 0.0);
  const int threads = o.threads > 0 ? o.threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (long k = 0; k < static_cast<long>(o.realizations); ++k) {
    Field u = Field::gaussian(lambda, w0, n, spacing_at(0.0));
    for (std::size_t s = 0; s < planes.size(); ++s) {
      const Plane& p = planes[s];
      if (steps[s]) steps[s]->execute(u);
      if (p.screen >= 0) {
        // Screen j of realisation k: its own stream per screen (the seed mixed with j), index k.
        const std::uint64_t stream = o.seed ^ (0x9E3779B97F4A7C15ULL * static_cast<std::uint64_t>(p.screen + 1));
        apply_phase_screen(u, generators[p.screen]->generate(stream, static_cast<std::size_t>(k)));
      }
      if (p.range >= 0)
        out.overlap[k][p.range] = detail::overlap_from_irradiance(system, receivers[p.range], u, p.z, grids[p.range]);
    }
    const Vec2 c = u.centroid();
    out.wander_x[k] = c.x;
    out.wander_y[k] = c.y;
    out.radius_last[k] = u.beam_radius();
  }
  return out;
}

}  // namespace lidar_overlap
