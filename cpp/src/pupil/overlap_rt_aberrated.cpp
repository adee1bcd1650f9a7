#include "lidar_overlap/pupil/overlap_rt_aberrated.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

#include "lidar_overlap/pupil/zernike.hpp"
#include "pupil/aberrated_pupil_integral.hpp"
#include "pupil/seidel_gradient.hpp"
#include "core/checks.hpp"
#include "core/constants.hpp"
#include "core/entry_checks.hpp"
#include "core/parallel.hpp"
#include "core/quadrature.hpp"

namespace lidar_overlap {

namespace {

// The ray fan through the pupil, with the field-independent wavefront slope of every ray computed once.
class RayFan {
 public:
  RayFan(const LidarSystem& system, const Aberrations& aberrations,
         const RtAberratedOptions& options)
      : system_(system), ab_(aberrations), rings_(options.rings), per_ring_(options.ring_rays) {
    radius_ = 0.5 * system.telescope.diameter;
    Aberrations fixed = aberrations;  // the part that is the same for every scatterer
    fixed.w131 = fixed.w222 = fixed.w220 = fixed.w311 = 0.0;
    for (std::size_t i = 0; i < rings_; ++i) {
      const double rho = std::sqrt((i + 0.5) / rings_);  // midpoints in rho^2: equal areas
      for (std::size_t k = 0; k < per_ring_; ++k) {
        const double theta = 2.0 * kPi * k / per_ring_;
        const Vec2 p{rho * std::cos(theta), rho * std::sin(theta)};
        pupil_.push_back(p);
        slope_.push_back((1.0 / radius_) * fixed.gradient(p));
      }
    }
  }

  // Fraction of the scatterer's rays into the full aperture that reach the detector.
  double coupling(double z, Vec2 position) const {
    const Telescope& t = system_.telescope;
    const Detector& det = system_.detector;
    const double d = t.focal_length + det.defocus, k = 1.0 / z - 1.0 / t.focal_length;
    const double max_slope = det.max_ray_slope();
    const Vec2 field = (1.0 / z) * position,
               h = ab_.field_dependent() ? (1.0 / ab_.field_radius) * field : Vec2{};
    const double s_obs = t.obstruction_distance / z;
    std::vector<double> margin(per_ring_);
    double total = 0.0;
    for (std::size_t i = 0; i < rings_; ++i) {
      for (std::size_t j = 0; j < per_ring_; ++j) {
        const std::size_t r = i * per_ring_ + j;
        const Vec2 a = radius_ * pupil_[r];
        Vec2 slope = k * a - (1.0 / z) * position + slope_[r];
        if (ab_.field_dependent()) {  // Seidel field terms, gradient in the normalised pupil
          const Vec2 p = pupil_[r];
          const detail::SeidelFieldGradient g = detail::seidel_field_gradient(ab_, p, h);
          slope = slope + (1.0 / radius_) * (g.along_pupil * p + g.along_field * h);
        }
        double m = det.radius - norm(a + d * slope - det.offset);
        if (t.obstruction_radius > 0.0)
          m = std::min(m, norm(a + s_obs * (position - a)) - t.obstruction_radius);
        if (det.numerical_aperture) m = std::min(m, max_slope - norm(slope));
        margin[j] = m;
      }
      // Share of the ring with margin > 0, the sign changes placed by linear interpolation (periodic ring).
      double inside = 0.0;
      for (std::size_t j = 0; j < per_ring_; ++j) {
        const double m0 = margin[j], m1 = margin[(j + 1) % per_ring_];
        if (m0 > 0.0 && m1 > 0.0)
          inside += 1.0;
        else if (m0 > 0.0 || m1 > 0.0)
          inside += std::max(m0, m1) / std::abs(m1 - m0);
      }
      total += inside;
    }
    return total / static_cast<double>(rings_ * per_ring_);
  }

 private:
  const LidarSystem& system_;
  const Aberrations& ab_;
  std::size_t rings_, per_ring_;
  double radius_ = 0.0;
  std::vector<Vec2> pupil_, slope_;
};

bool rotationally_symmetric(const LidarSystem& system, const Aberrations& ab) {
  if (!system.is_axisymmetric()) return false;
  for (std::size_t i = 0; i < ab.zernike.size(); ++i)
    if (ab.zernike[i] != 0.0 && noll_index(static_cast<int>(i + 1)).m != 0) return false;
  return true;  // Seidel terms turn with the field direction: the coupling depends on |P| only
}

void validate(const LidarSystem& system, const Aberrations& aberrations,
              const RtAberratedOptions& o) {
  system.validate();
  aberrations.validate();
  if (o.rings < 4) checks::fail("rings", static_cast<double>(o.rings), "at least 4");
  if (o.ring_rays < 8) checks::fail("ring_rays", static_cast<double>(o.ring_rays), "at least 8");
  if (o.directions < 4) checks::fail("directions", static_cast<double>(o.directions), "at least 4");
  checks::tolerance("tolerance", o.tolerance);
  detail::thread_count(o.threads);
  if (o.max_segments < 1) checks::fail("max_segments", 0.0, "at least 1");
}

}  // namespace

RtAberratedOverlap overlap_rt_aberrated(const LidarSystem& system, const Aberrations& aberrations,
                                        const std::vector<double>& ranges,
                                        const RtAberratedOptions& options) {
  validate(system, aberrations, options);
  const int threads = detail::checked_threads_and_ranges(system, ranges, options.threads);
  const RayFan fan(system, aberrations, options);
  RtAberratedOverlap out;
  out.rotationally_symmetric = rotationally_symmetric(system, aberrations);
  const std::size_t n = ranges.size();
  out.overlap.assign(n, 0.0);
  out.error_estimate.assign(n, 0.0);
  out.converged.assign(n, true);
  std::vector<char> converged(n, 1);
  const std::size_t directions = out.rotationally_symmetric ? 1 : options.directions;
  // Each coupling traces rings x ring_rays rays. The radial integrals of one range may trace kMaxFanRays in all
  // (a few seconds); past that they stop short of the tolerance, which clears `converged` (and warns in Python).
  const double rays_per_segment =
      21.0 * double(options.rings) * double(options.ring_rays) * double(directions);
  const std::size_t fan_segments = std::min<std::size_t>(
      options.max_segments,
      std::max<std::size_t>(8, checks::saturate(kMaxFanRays / rays_per_segment)));
  const Telescope& t = system.telescope;
  const bool dual = !aberrations.field_dependent() && !system.detector.numerical_aperture &&
                    (t.obstruction_radius == 0.0 || t.obstruction_distance == 0.0);
  out.pupil_form = dual;
  std::optional<detail::AberratedPupilIntegral> pupil;
  if (dual) pupil.emplace(system, aberrations, ranges, out.rotationally_symmetric);
  detail::parallel_for(n, threads, [&](std::size_t i) {
    if (pupil) {
      std::tie(out.overlap[i], out.error_estimate[i]) = pupil->at(i);
      return;
    }
    const double z = ranges[i], w = system.beam.radius(z), var = 0.25 * w * w;
    const Vec2 c = system.beam.center(z);
    // The mean over directions of the radial beam integral, by the trapezoid rule (spectral for this periodic
    // function), doubling the directions from 8 until two rules agree within the tolerance or the cap.
    double sum = 0.0, radial_error = 0.0, value = 0.0, change = 0.0;
    auto add_direction = [&](double alpha) {
      const Vec2 dir{std::cos(alpha), std::sin(alpha)};
      // Rayleigh density of the distance from the beam centre (sigma = w/2), cut at 5 w (exp(-50)).
      auto integrand = [&](double r) {
        detail::cancellation_point();
        return r / var * std::exp(-0.5 * r * r / var) * fan.coupling(z, c + r * dir);
      };
      const double points[2] = {0.0, 5.0 * w};
      const QuadratureResult q = integrate(integrand, points, 2, options.tolerance, fan_segments);
      sum += q.value;
      radial_error += q.error;
      if (!q.converged) converged[i] = 0;
    };
    std::size_t count = std::min<std::size_t>(directions, 8);
    for (std::size_t j = 0; j < count; ++j) add_direction(2.0 * kPi * j / count);
    value = sum / count;
    while (count < directions) {
      for (std::size_t j = 0; j < count; ++j)
        add_direction(2.0 * kPi * (j + 0.5) / count);  // the midpoints
      count *= 2;
      change = std::abs(sum / count - value);
      value = sum / count;
      if (change <= options.tolerance) break;
    }
    const double error = radial_error / count + change;
    out.overlap[i] = value;
    out.error_estimate[i] = error;
  });
  for (std::size_t i = 0; i < n; ++i) out.converged[i] = converged[i] != 0;
  double slack = options.tolerance;
  for (double e : out.error_estimate) slack = std::max(slack, e);
  checks::overlap_values(out.overlap, ranges, slack, "overlap_rt_aberrated");
  return out;
}

double emitter_coupling_rt_aberrated(const LidarSystem& system, const Aberrations& aberrations,
                                     double z, Vec2 position, const RtAberratedOptions& options) {
  validate(system, aberrations, options);
  system.validate_range(z, "z");
  checks::coordinate("position", position);
  std::vector<double> g{RayFan(system, aberrations, options).coupling(z, position)};
  checks::overlap_values(g, {z}, 1e-9, "emitter_coupling_rt_aberrated");
  return g[0];
}

}  // namespace lidar_overlap
