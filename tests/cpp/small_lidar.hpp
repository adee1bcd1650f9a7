// The C++ tests' small coaxial lidar for turbulence on both paths: 1064 nm, w0 = 5 mm, D = 5 cm, f = 0.5 m,
// a detector of the given radius (90 um: 0.36 mrad full field of view; 45 um: 4 diffraction widths).
#pragma once

#include "lidar_overlap/core/system.hpp"

namespace test {

inline lidar_overlap::LidarSystem small_lidar(double detector_radius) {
  lidar_overlap::LidarSystem s;
  s.beam = lidar_overlap::GaussianBeam{1064e-9, 5e-3};
  s.telescope = lidar_overlap::Telescope{0.05, 0.5, 0.0, 0.0};
  s.detector.radius = detector_radius;
  return s;
}

}  // namespace test
