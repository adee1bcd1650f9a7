// The receiver and the whole lidar: telescope (ideal thin lens at the aperture stop, optional
// central obstruction in front of it) and detector (fibre core or field stop) behind it.
#pragma once

#include <optional>
#include <string>

#include "lidar_overlap/core/beam.hpp"
#include "lidar_overlap/core/vec2.hpp"

namespace lidar_overlap {

struct Telescope {
  double diameter = 0.15;             // m, aperture stop diameter D
  double focal_length = 1.0;          // m, effective focal length f
  double obstruction_radius = 0.0;    // m, opaque central disc, 0 <= r_obs < D/2
  double obstruction_distance = 0.0;  // m, distance of that disc in front of the aperture stop

  void validate() const;
};

struct Detector {
  double radius = 0.45e-3;                   // m, detector (fibre core, field stop) radius r_d
  double defocus = 0.0;                      // m, displacement behind the focal plane (> -f)
  Vec2 offset;                               // m, detector centre in its plane
  std::optional<double> numerical_aperture;  // accepted sin(angle); empty: accepts every ray
  // A second stop behind the lens (a relay's or field lens's aperture, a vignetting mount): a centred
  // disc of radius stop_radius (m) in the plane stop_distance (m) behind the lens, before the detector
  // plane. Empty: no such stop (stop_distance must then be 0).
  std::optional<double> stop_radius;
  double stop_distance = 0.0;

  void validate() const;
  // tan(asin NA): the steepest ray slope behind the lens that the detector accepts (rad, paraxial);
  // infinity without a numerical aperture.
  double max_ray_slope() const;
  // The detector that sees a full field of view `fov` (rad, full angle) through focal length f (m).
  static Detector from_fov(double fov, double focal_length, double defocus = 0.0, Vec2 offset = {},
                           std::optional<double> numerical_aperture = std::nullopt);
};

struct LidarSystem {
  GaussianBeam beam;
  Telescope telescope;
  Detector detector;

  // Validates every part and their relations (obstruction inside the aperture, detector plane
  // behind the lens).
  void validate() const;
  // Checks a range z (m): positive, finite, beyond the obstruction. `parameter` names it in errors.
  void validate_range(double z, const std::string& parameter = "z") const;
  // True when beam, obstruction and detector share the telescope axis.
  bool is_axisymmetric() const;
};

}  // namespace lidar_overlap
