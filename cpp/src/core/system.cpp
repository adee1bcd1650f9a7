#include "lidar_overlap/core/system.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "lidar_overlap/core/limits.hpp"
#include "core/checks.hpp"

namespace lidar_overlap {

void Telescope::validate() const {
  checks::length("telescope.diameter", diameter);
  checks::length("telescope.focal_length", focal_length);
  checks::non_negative("telescope.obstruction_radius", obstruction_radius);
  checks::non_negative("telescope.obstruction_distance", obstruction_distance);
  checks::coordinate("telescope.obstruction_distance", obstruction_distance);
  if (obstruction_radius > 0.0) checks::length("telescope.obstruction_radius", obstruction_radius);
  if (!(obstruction_radius < 0.5 * diameter))
    checks::fail(
        "telescope.obstruction_radius", obstruction_radius,
        "a value smaller than the aperture radius " + checks::number(0.5 * diameter) + " m");
}

void Detector::validate() const {
  checks::length("detector.radius", radius);
  checks::coordinate("detector.defocus", defocus);
  checks::coordinate("detector.offset", offset);
  if (numerical_aperture) {
    const double na = *numerical_aperture;
    if (!(na > 0.0 && na < 1.0))
      checks::fail("detector.numerical_aperture", na, "a value in (0, 1)");
  }
  if (stop_radius) {
    checks::length("detector.stop_radius", *stop_radius);
    checks::length("detector.stop_distance", stop_distance);
  } else if (stop_distance != 0.0) {
    checks::fail("detector.stop_distance", stop_distance,
                 "0 without a stop_radius (no second stop)");
  }
}

double Detector::max_ray_slope() const {
  if (!numerical_aperture) return std::numeric_limits<double>::infinity();
  const double na = *numerical_aperture;
  return na / std::sqrt(1.0 - na * na);
}

Detector Detector::from_fov(double fov, double focal_length, double defocus, Vec2 offset,
                            std::optional<double> numerical_aperture) {
  checks::positive("fov", fov);
  checks::angle("fov", 0.5 * fov);
  checks::length("focal_length", focal_length);
  if (!(0.5 * fov * focal_length >= kMinLength))
    checks::fail("fov", fov,
                 "a field of view giving a detector radius fov f / 2 of at least 1e-10 m");
  Detector d{0.5 * fov * focal_length, defocus, offset, numerical_aperture, std::nullopt, 0.0};
  d.validate();
  return d;
}

void LidarSystem::validate() const {
  beam.validate();
  telescope.validate();
  detector.validate();
  if (!(telescope.focal_length + detector.defocus > 0.0))
    checks::fail("detector.defocus", detector.defocus,
                 "a value > -focal_length = " + checks::number(-telescope.focal_length) +
                     " m (the detector plane must lie behind the lens)");
  const double image_distance = telescope.focal_length + detector.defocus;
  if (detector.stop_radius && !(detector.stop_distance < image_distance))
    checks::fail(
        "detector.stop_distance", detector.stop_distance,
        "a distance behind the lens < that of the detector plane, focal_length + defocus = " +
            checks::number(image_distance) + " m");
}

void LidarSystem::validate_range(double z, const std::string& parameter) const {
  checks::length(parameter, z);
  if (telescope.obstruction_radius > 0.0 && !(z > telescope.obstruction_distance))
    checks::fail(parameter, z,
                 "a range beyond the obstruction distance " +
                     checks::number(telescope.obstruction_distance) + " m");
}

bool LidarSystem::is_axisymmetric() const {
  return beam.on_axis() && detector.offset.x == 0.0 && detector.offset.y == 0.0;
}

}  // namespace lidar_overlap
