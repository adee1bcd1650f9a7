// The transmitted beam of the ray-tracing path: a Gaussian (TEM00-like) irradiance profile whose
// 1/e^2 radius grows with range and whose centroid follows the beam's offset and tilt (paper B1-B6).
#pragma once

#include <optional>

#include "lidar_overlap/core/vec2.hpp"

namespace lidar_overlap {

// How the 1/e^2 radius grows with range z.
enum class WidthLaw {
  gaussian,  // w(z)^2 = w0^2 + (theta z)^2   (exact for a beam with its waist at z = 0)
  linear,    // w(z) = w0 + theta z          (the paper's marginal ray, Appendix B)
};

struct GaussianBeam {
  double wavelength = 355e-9;        // m
  double waist_radius = 1e-3;        // m, 1/e^2 irradiance radius at the transmitting plane z = 0
  std::optional<double> divergence;  // rad, 1/e^2 far-field half-angle; empty: lambda / (pi w0)
  Vec2 offset;                       // m, centroid position at z = 0 relative to the telescope axis
  Vec2 tilt;                         // rad, centroid angle relative to the telescope axis
  WidthLaw width_law = WidthLaw::gaussian;

  // Throws std::invalid_argument naming the first invalid member.
  void validate() const;

  // Far-field 1/e^2 half-angle divergence theta (rad).
  double half_angle_divergence() const;
  // 1/e^2 irradiance radius w(z) (m) at range z (m).
  double radius(double z) const;
  // Centroid position (m) at range z (m): offset + tilt z.
  Vec2 center(double z) const;
  // Irradiance (W/m^2 per W transmitted) at transverse position p (m) and range z (m).
  double irradiance(Vec2 p, double z) const;
  // True when the beam axis coincides with the telescope axis (no offset, no tilt).
  bool on_axis() const;
  // Throws std::invalid_argument unless Fourier optics can model the beam: the Gaussian width law and a
  // divergence at or above the diffraction limit lambda / (pi w0) (M^2 >= 1).
  void validate_for_fourier_optics() const;
};

}  // namespace lidar_overlap
