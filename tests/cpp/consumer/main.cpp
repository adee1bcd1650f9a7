// Computes one overlap value of the paper's Table 1 system in the point-aperture limit and checks it
// against the closed form 1 - exp(-2 (alpha z)^2 / w(z)^2).
#include <lidar_overlap/lidar_overlap.hpp>

#include <cmath>
#include <iostream>

int main() {
  using namespace lidar_overlap;
  LidarSystem system;
  system.detector = Detector::from_fov(0.9e-3, 1.0);
  system.telescope.diameter = 1e-7;
  const double z = 300.0;
  const double g = overlap_rt(system, {z}, {1e-9, 1, 4000}).overlap[0];
  const double w = system.beam.radius(z), az = system.detector.radius * z;
  const double expected = -std::expm1(-2.0 * az * az / (w * w));
  std::cout << "lidar_overlap " << kVersion << ": G(" << z << " m) = " << g << " (closed form " << expected << ")\n";
  return std::abs(g - expected) < 1e-7 ? 0 : 1;
}
