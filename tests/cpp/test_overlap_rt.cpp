// RT overlap from C++ against closed forms: point-aperture limit, far-range obstruction limit,
// in-focus defocused detector (Eq. 5), and thread-count independence.
#include <cmath>
#include <vector>

#include "check.hpp"
#include "lidar_overlap/lidar_overlap.hpp"

using namespace lidar_overlap;

int main() {
  LidarSystem s;  // defaults: the paper's Table 1 system at 355 nm
  s.telescope.diameter = 1e-7;  // point aperture: G = 1 - exp(-2 (alpha z)^2 / w^2), alpha = r_d / f
  std::vector<double> z;
  for (double r = 1.0; r <= 2000.0; r *= 1.5) z.push_back(r);
  const RtOverlap point = overlap_rt(s, z, {1e-8, 0, 4000});
  for (std::size_t i = 0; i < z.size(); ++i) {
    const double w = s.beam.radius(z[i]), az = s.detector.radius / s.telescope.focal_length * z[i];
    test::near("point aperture z=" + std::to_string(z[i]), point.overlap[i], -std::expm1(-2 * az * az / (w * w)), 1e-7);
  }

  LidarSystem obs;
  obs.telescope.obstruction_radius = 0.02;
  obs.telescope.obstruction_distance = 0.7;
  const double far = 1.0 - std::pow(0.02 / 0.075, 2);
  const RtOverlap o = overlap_rt(obs, {2e4, 5e4}, {1e-8, 0, 4000});
  test::near("obstruction far-range limit", o.overlap[1], far, 2e-5);

  // A point scatterer on axis at z_opt images to a point on a defocused detector: coupling 1.
  LidarSystem def;
  def.detector.defocus = 5e-3;
  const double zopt = optimal_focus_range(1.0, 5e-3);
  test::near("z_opt (Eq. 5)", zopt, 1.0 * 1.005 / 0.005, 1e-9);
  test::near("coupling at z_opt", emitter_coupling_rt(def, zopt, {0, 0}), 1.0, 1e-12);

  RtOptions one{1e-6, 1, 4000}, two{1e-6, 2, 4000};
  LidarSystem tilted;
  tilted.beam.tilt = {0.2e-3, 0.0};
  const RtOverlap t1 = overlap_rt(tilted, z, one), t2 = overlap_rt(tilted, z, two);
  test::that("thread count does not change results", t1.overlap == t2.overlap);
  return test::report("test_overlap_rt");
}
