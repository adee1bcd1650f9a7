// Grid choice from C++: the power radii of a TEM00 field against their closed forms, the padded
// angular-spectrum propagation against Eq. (D1), zero padding that keeps the field centred, and the cap.
#include <cmath>

#include "check.hpp"
#include "lidar_overlap/fourier/grid_choice.hpp"
#include "core/constants.hpp"

using namespace lidar_overlap;

int main() {
  const double w0 = 0.2e-3, lambda = 1064e-9, dx = w0 / 16.0, zr = kPi * w0 * w0 / lambda;
  const Field beam = Field::gaussian(lambda, w0, 128, dx);
  // All but 1e-7 of exp(-2 r^2 / w^2) lies inside w sqrt(ln(1e7) / 2); the radii come from bins of one
  // sample (spatial) and one frequency step (angular), hence the tolerances.
  const double r_fraction = std::sqrt(std::log(1e7) / 2.0);
  const GridChoice g = choose_grid(beam, 3.0 * zr, PropagationMethod::angular_spectrum);
  test::near("input radius", g.input_radius, r_fraction * w0, dx);
  test::near("angular radius", g.angular_radius, r_fraction * lambda / (kPi * w0),
             lambda / (128 * dx));
  test::near("output radius bound", g.output_radius, g.input_radius + 3.0 * zr * g.angular_radius,
             1e-15);
  test::near("padded to a power of two", static_cast<double>(g.n & (g.n - 1)), 0.0, 0.0);

  const Field padded = zero_pad(beam, g.n);
  test::near("zero padding keeps the centroid", norm(padded.centroid()), 0.0, 1e-12 * w0);
  test::near("zero padding keeps the power", padded.power(), beam.power(), 1e-14);
  const Propagated p = propagate(padded, 3.0 * zr, g.method);
  test::near("D1 on the chosen grid", p.field.beam_radius() / (w0 * std::sqrt(10.0)), 1.0, 1e-5);
  test::near("no wrap-around on the chosen grid", p.report.output_edge_power, 0.0, 1e-6);

  test::throws(
      "cap on the grid",
      [&] { choose_grid(beam, 300.0 * zr, PropagationMethod::angular_spectrum, 4096); },
      "grid_size");
  test::throws("padding to a smaller grid", [&] { zero_pad(beam, 64); }, "grid_size");
  return test::report("test_grid_choice");
}
