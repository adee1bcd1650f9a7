#include "fourier/fo_receiver.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/checks.hpp"
#include "core/constants.hpp"
#include "core/special_functions.hpp"
#include "core/parallel.hpp"
#include "core/quadrature.hpp"

namespace lidar_overlap {

FoReceiver::FoReceiver(const LidarSystem& system, double z, const std::string& parameter) {
  system.validate();
  system.validate_range(z, parameter);
  const Telescope& t = system.telescope;
  const Detector& det = system.detector;
  wavelength_ = system.beam.wavelength;
  z_ = z;
  d_ = t.focal_length + det.defocus;
  r_d_ = det.radius;
  const double radius = 0.5 * t.diameter;
  area_ = kPi * radius * radius;
  pupil_.outer = radius;
  if (det.numerical_aperture) {
    // The NA cone as a pupil disc (its centre moves with the scatterer, neglected: see overlap_fo.hpp).
    const double k = 1.0 / z - 1.0 / t.focal_length;
    if (k != 0.0) pupil_.outer = std::min(radius, det.max_ray_slope() / std::abs(k));
  }
  if (det.stop_radius) {
    // The second stop as a pupil disc of radius r_s / |1 + s/z - s/f|, like the NA cone: its centre, P s / (z m_s)
    // for a scatterer at P, is neglected (exact on the axis; docs/receiver_stop.md).
    const double s = det.stop_distance, ms = 1.0 + s / z - s / t.focal_length;
    if (ms != 0.0) pupil_.outer = std::min(pupil_.outer, *det.stop_radius / std::abs(ms));
  }
  if (t.obstruction_radius > 0.0)
    pupil_.inner = t.obstruction_radius * z / (z - t.obstruction_distance);
  if (pupil_.inner >= pupil_.outer) pupil_.outer = pupil_.inner = 0.0;  // nothing passes
  // Spherical wave from the scatterer (1/z), lens (-1/f), propagation to the detector plane (1/d).
  pupil_.psi = kPi / wavelength_ * (1.0 / z - 1.0 / t.focal_length + 1.0 / d_);
  const double phase =
      4.0 * std::abs(pupil_.psi) * pupil_.outer * pupil_.outer;  // bounds every OTF argument
  if (!(phase <= kMaxPupilPhase))
    checks::fail(parameter, z,
                 "a range where the defocus phase across the pupil (here " + checks::number(phase) +
                     " rad) is at most " + checks::number(kMaxPupilPhase) +
                     " rad: the image is geometric there, where method 'rt' is exact");
}

double FoReceiver::otf_cost() const {
  return 4.0 * std::abs(pupil_.psi) * pupil_.outer * pupil_.outer + 50.0;
}

double FoReceiver::blur_radius() const {
  return pupil_.outer * d_ * std::abs(pupil_.psi * wavelength_ / kPi);
}

double FoReceiver::tail_period(double max_error) const {
  // Far from its core a point image falls, averaged over its rings, as lambda d P / (4 pi^3 A s^3) (edge
  // diffraction: P the pupil's edge length, A its area; lambda d / (pi^3 D s^3) for a disc), so the
  // detector disc at distance s collects r_d^2 lambda d P / (4 pi^2 A s^3). Over the square lattice
  // without its origin, sum |m|^-3 = 9.03.
  const double edge_over_area = 2.0 / (pupil_.outer - pupil_.inner);
  return std::cbrt(9.03 * r_d_ * r_d_ * wavelength_ * d_ * edge_over_area /
                   (4.0 * kPi * kPi * max_error));
}

double FoReceiver::point_coupling(double offset) const {
  if (pupil_.outer == 0.0) return 0.0;
  const double qc = cutoff();
  // Breakpoints closer than the shortest oscillation of disc^, J0 and the OTF.
  const double scale = std::max({r_d_, offset, blur_radius(), wavelength_ * d_ / pupil_.outer});
  const std::size_t pieces = std::min<std::size_t>(20000, 2 + checks::saturate(2.0 * qc * scale));
  // ~2 adaptive panels of 21 nodes per piece, each node one OTF evaluation.
  checks::count_from(
      42.0 * pieces * otf_cost(), static_cast<std::size_t>(kMaxOtfWork), "z", z_,
      "Bessel terms: the point's image spans " + checks::number(scale) +
          " m, many resolutions, with a defocus phase of " + checks::number(otf_cost()) +
          " rad across the pupil; the image is geometric there, where method 'rt' is exact");
  std::vector<double> points(pieces + 1);
  for (std::size_t i = 0; i <= pieces; ++i) points[i] = qc * static_cast<double>(i) / pieces;
  auto integrand = [&](double q) {
    detail::cancellation_point();
    return otf(q) * disc_transform(r_d_, q) * bessel_j0(2.0 * kPi * q * offset) * 2.0 * kPi * q;
  };
  return integrate(integrand, points.data(), points.size(), 1e-10 * area_, 100000).value / area_;
}

}  // namespace lidar_overlap
