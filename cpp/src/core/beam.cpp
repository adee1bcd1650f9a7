#include "lidar_overlap/core/beam.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "lidar_overlap/core/limits.hpp"
#include "core/checks.hpp"
#include "core/constants.hpp"

namespace lidar_overlap {

void GaussianBeam::validate() const {
  checks::length("beam.wavelength", wavelength);
  checks::length("beam.waist_radius", waist_radius);
  const double theta_d = wavelength / (kPi * waist_radius);
  const bool diffraction_limited_law = !divergence || width_law == WidthLaw::gaussian;
  if (diffraction_limited_law && !(theta_d <= kMaxAngle))
    checks::fail("beam.waist_radius", waist_radius,
                 "a waist of at least lambda / (pi x " + checks::number(kMaxAngle) +
                     " rad) = " + checks::number(wavelength / (kPi * kMaxAngle)) +
                     " m: a smaller one diffracts beyond the paraxial model");
  if (divergence) {
    checks::positive("beam.divergence", *divergence);
    checks::angle("beam.divergence", *divergence);
    // A Gaussian beam cannot spread less than its diffraction limit (M^2 >= 1). The linear law is the
    // paper's geometric marginal-ray model and takes any divergence (ray tracing only).
    if (width_law == WidthLaw::gaussian && *divergence < theta_d * (1.0 - 1e-9))
      checks::fail(
          "beam.divergence", *divergence,
          "at least the diffraction limit lambda / (pi w0) = " + checks::number(theta_d) +
              " rad (M^2 >= 1); width_law 'linear' takes any divergence (ray tracing only)");
  }
  checks::coordinate("beam.offset", offset);
  checks::angle("beam.tilt", tilt);
}

double GaussianBeam::half_angle_divergence() const {
  return divergence ? *divergence : wavelength / (kPi * waist_radius);
}

double GaussianBeam::radius(double z) const {
  const double theta = half_angle_divergence();
  if (width_law == WidthLaw::linear) return waist_radius + theta * z;
  return std::hypot(waist_radius, theta * z);
}

Vec2 GaussianBeam::center(double z) const { return offset + z * tilt; }

double GaussianBeam::irradiance(Vec2 p, double z) const {
  const double w = radius(z);
  const Vec2 d = p - center(z);
  return 2.0 / (kPi * w * w) * std::exp(-2.0 * dot(d, d) / (w * w));
}

bool GaussianBeam::on_axis() const {
  return offset.x == 0.0 && offset.y == 0.0 && tilt.x == 0.0 && tilt.y == 0.0;
}

void GaussianBeam::validate_for_fourier_optics() const {
  if (width_law != WidthLaw::gaussian)
    throw std::invalid_argument(
        "beam.width_law = 'linear' is invalid for Fourier optics: expected 'gaussian' "
        "(the linear law is the paper's RT marginal-ray model)");
}

}  // namespace lidar_overlap
