// Flat-top design from C++: the paper's plate (w0 = 1 mm, 355 nm, 0.36 mrad) converges with a monotone
// error, keeps the power in both planes (Parseval) and meets its plateau and edge; a disc narrower than
// the TEM00 divergence is refused naming the parameter.
#include <cmath>
#include <numeric>

#include "check.hpp"
#include "lidar_overlap/beams/flat_top.hpp"
#include "core/constants.hpp"

using namespace lidar_overlap;

int main() {
  const double lambda = 355e-9, w0 = 1e-3, psi = 0.36e-3;
  const FlatTopDesign d = design_flat_top(lambda, w0, psi);
  test::near("stops converged", d.stop == FlatTopStop::converged ? 1.0 : 0.0, 1.0, 0.0);
  test::near("error never rises", d.monotone ? 1.0 : 0.0, 1.0, 0.0);
  test::near("plate power", d.transmitted.power(), 1.0, 1e-10);
  const double far_power = std::accumulate(d.far_field.begin(), d.far_field.end(), 0.0) *
                           d.angular_spacing * d.angular_spacing;
  test::near("far-field power (Parseval)", far_power, 1.0, 1e-10);
  // The paper's case reaches 2.6 % rms and 9 % peak-to-valley on the plateau (see tests/test_flat_top.py).
  test::near("plateau rms", d.uniformity_rms, 0.015, 0.015);
  test::near("plateau peak-to-valley", d.uniformity_pv, 0.05, 0.05);
  test::near("edge width / target", d.edge_width / d.edge_width_target, 1.0, 0.1);
  test::throws(
      "below the TEM00 divergence", [&] { design_flat_top(lambda, w0, 2.0 * lambda / (kPi * w0)); },
      "angular_diameter");
  return test::report("test_flat_top");
}
