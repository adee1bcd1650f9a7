// Fourier-optics receiver from C++: the OTF of a clear, in-focus pupil against the classic
// (2/pi)(acos s - s sqrt(1 - s^2)), the full-arc identity for a defocused pupil at zero shift, and the
// in-focus point coupling against the Airy encircled energy 1 - J0^2(v) - J1^2(v).
#include <cmath>

#include "check.hpp"
#include "lidar_overlap/fourier/overlap_fo.hpp"
#include "core/constants.hpp"
#include "fourier/otf.hpp"

using namespace lidar_overlap;

int main() {
  const double r = 0.075, area = kPi * r * r;
  for (double s : {0.0, 0.1, 0.37, 0.8, 0.99}) {
    const double expected = 2.0 / kPi * (std::acos(s) - s * std::sqrt(1.0 - s * s));
    test::near("in-focus OTF at s=" + std::to_string(s),
               annular_otf({r, 0.0, 0.0}, 2.0 * r * s) / area, expected, 1e-12);
  }
  test::near("OTF beyond the cutoff", annular_otf({r, 0.0, 0.0}, 2.0 * r * 1.01), 0.0, 0.0);
  // At zero shift the phase cancels whatever the defocus: OTF(0) is the annulus area.
  test::near("defocused annulus at zero shift",
             annular_otf({r, 0.02, 3e5}, 0.0) / (kPi * (r * r - 0.02 * 0.02)), 1.0, 1e-12);

  LidarSystem s;  // the paper's Table 1 receiver: f = 1 m, D = 0.15 m
  for (double radius : {2e-6, 1e-5, 1e-4}) {
    s.detector.radius = radius;
    const double v =
        kPi * s.telescope.diameter * radius / (s.beam.wavelength * s.telescope.focal_length);
    const double ee =
        1.0 - std::pow(std::cyl_bessel_j(0.0, v), 2) - std::pow(std::cyl_bessel_j(1.0, v), 2);
    test::near("Airy encircled energy, r_d=" + std::to_string(radius),
               emitter_coupling_fo(s, 1e9, {0, 0}), ee, 1e-8);
  }
  return test::report("test_overlap_fo");
}
