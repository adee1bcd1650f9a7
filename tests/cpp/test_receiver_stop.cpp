// A second stop behind the lens (Detector::stop_radius at stop_distance): the coupling of an on-axis point
// against the closed form (r_s / (R |1 + s/z - s/f|))^2, a stop that cuts nothing, the stop in focus (a gate),
// and invalid stops named in errors.
#include <cmath>
#include <limits>

#include "check.hpp"
#include "lidar_overlap/lidar_overlap.hpp"

using namespace lidar_overlap;

int main() {
  LidarSystem s;  // Table 1: D = 0.15 m, f = 1 m, r_d = 0.45 mm
  const double R = 0.075,
               z = 1e4;  // at 10 km the point image (7.5 um) lies well inside the detector
  LidarSystem stop = s;
  stop.detector.stop_radius = 0.03;
  stop.detector.stop_distance = 0.5;
  const double m = 1.0 + 0.5 / z - 0.5;
  test::near("on-axis point through the stop", emitter_coupling_rt(stop, z, {0, 0}),
             std::pow(0.03 / (m * R), 2), 1e-12);
  // the stop's pupil disc r_s / m is centred on P s / (z m): a point 2 m off axis moves it 0.2 mm, still inside
  test::near("off-axis point", emitter_coupling_rt(stop, z, {2.0, 0}), std::pow(0.03 / (m * R), 2),
             1e-12);
  LidarSystem wide = stop;
  wide.detector.stop_radius = 0.05;  // pupil radius 0.1 m > R: cuts nothing
  test::near("a stop wider than the beam of rays", emitter_coupling_rt(wide, z, {0, 0}),
             emitter_coupling_rt(s, z, {0, 0}), 1e-15);
  // behind the focal plane of a defocused detector the stop is in focus at z_s = s f / (s - f): the condition is
  // |P| s / z_s <= r_s, independent of the aperture point
  LidarSystem gate = s;
  gate.detector.defocus = 5e-3;
  gate.detector.stop_distance = 1.0025;
  gate.detector.stop_radius = 1e-4;
  const double zs = 1.0025 / 0.0025;       // 401 m (m_s zero or within rounding of it)
  const double edge = 1e-4 * zs / 1.0025;  // 4 cm: the point's image stays on the detector
  test::that("inside the gate", emitter_coupling_rt(gate, zs, {0.5 * edge, 0}) > 0.0);
  test::near("outside the gate", emitter_coupling_rt(gate, zs, {1.5 * edge, 0}), 0.0, 0.0);

  const double nan = std::numeric_limits<double>::quiet_NaN(),
               inf = std::numeric_limits<double>::infinity();
  auto with = [&](std::optional<double> radius, double distance) {
    LidarSystem c = s;
    c.detector.stop_radius = radius;
    c.detector.stop_distance = distance;
    return c;
  };
  test::throws("stop radius 0", [&] { with(0.0, 0.5).validate(); }, "detector.stop_radius");
  test::throws("stop radius inf", [&] { with(inf, 0.5).validate(); }, "detector.stop_radius");
  test::throws("stop radius NaN", [&] { with(nan, 0.5).validate(); }, "detector.stop_radius");
  test::throws("stop distance 0", [&] { with(1e-3, 0.0).validate(); }, "detector.stop_distance");
  test::throws("stop distance NaN", [&] { with(1e-3, nan).validate(); }, "detector.stop_distance");
  test::throws(
      "stop at the detector plane", [&] { with(1e-3, 1.0).validate(); }, "detector.stop_distance");
  test::throws(
      "stop beyond the detector plane", [&] { with(1e-3, 3.0).validate(); }, "detector plane");
  test::throws(
      "distance without a stop", [&] { with(std::nullopt, 0.5).validate(); },
      "detector.stop_distance");
  return test::report("test_receiver_stop");
}
