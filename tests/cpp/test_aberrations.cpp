// Aberrations from C++: Zernike orthonormality on the pupil (polar Gauss rule), the pupil polynomial against
// direct evaluation, and a Zernike defocus Z4 in the pupil reproducing a moved detector in both paths (the
// detector-plane picture scales by f/d, so the detector radius is scaled with it).
#include <cmath>
#include <string>
#include <vector>

#include "check.hpp"
#include "lidar_overlap/pupil/aberrations.hpp"
#include "lidar_overlap/pupil/overlap_fo_aberrated.hpp"
#include "lidar_overlap/pupil/overlap_rt_aberrated.hpp"
#include "lidar_overlap/pupil/zernike.hpp"
#include "lidar_overlap/fourier/overlap_fo_radial.hpp"
#include "lidar_overlap/geometry/overlap_rt.hpp"
#include "core/constants.hpp"
#include "core/quadrature.hpp"

using namespace lidar_overlap;

int main() {
  // Mean of Z_i Z_j over the unit disc: Gauss-Legendre in rho^2 times the trapezoid rule in theta.
  const GaussLegendreRule& rule = gauss_legendre<24>();
  const int angles = 64;
  for (int i = 1; i <= 15; ++i)
    for (int j = i; j <= 15; ++j) {
      double mean = 0.0;
      for (std::size_t k = 0; k < rule.x.size(); ++k) {
        const double rho = std::sqrt(0.5 * (rule.x[k] + 1.0));
        for (int a = 0; a < angles; ++a) {
          const double t = 2.0 * kPi * a / angles;
          const Vec2 p{rho * std::cos(t), rho * std::sin(t)};
          mean += 0.5 * rule.w[k] / angles * zernike(i, p) * zernike(j, p);
        }
      }
      test::near("<Z" + std::to_string(i) + " Z" + std::to_string(j) + ">", mean,
                 i == j ? 1.0 : 0.0, 1e-12);
    }

  Aberrations ab;
  ab.zernike = {0.0, 1e-7, -2e-7, 3e-7, 0.0, 5e-8, 0.0, -4e-8, 0.0, 2e-8, 6e-8, 0.0, 1e-8};
  ab.w040 = 3e-8;
  const PupilPolynomial poly = ab.pupil_polynomial();
  std::vector<double> row(poly.degree + 1);
  for (Vec2 p : {Vec2{0.3, -0.2}, Vec2{-0.7, 0.5}, Vec2{0.0, 0.9}}) {
    poly.row(p.y, row.data());
    double w = 0.0;
    for (int k = poly.degree; k >= 0; --k) w = w * p.x + row[k];
    test::near("pupil polynomial at x=" + std::to_string(p.x), w, ab.wavefront(p), 1e-20);
  }

  const double defocus = 1e-3, f = 1.0, d = f + defocus, radius = 0.075;
  LidarSystem moved;  // Table 1 with the detector moved
  moved.detector.defocus = defocus;
  LidarSystem in_pupil;
  in_pupil.detector.radius = moved.detector.radius * f / d;
  Aberrations z4;
  z4.zernike = {0.0, 0.0, 0.0, (1.0 / d - 1.0 / f) * radius * radius / (4.0 * std::sqrt(3.0))};
  const std::vector<double> ranges{50.0, 300.0, 2000.0};
  RtOptions exact;
  exact.tolerance = 1e-10;
  const RtOverlap rt = overlap_rt(moved, ranges, exact);
  const RtAberratedOverlap rt_z4 = overlap_rt_aberrated(in_pupil, z4, ranges);
  const RadialFoOverlap fo = overlap_fo_radial(moved, ranges);
  const FoAberratedOverlap fo_z4 = overlap_fo_aberrated(in_pupil, z4, ranges);
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    const std::string at = " at " + std::to_string(ranges[i]) + " m";
    test::near("RT: Z4 in the pupil = moved detector" + at, rt_z4.overlap[i], rt.overlap[i], 1e-8);
    test::near("FO: Z4 in the pupil = moved detector" + at, fo_z4.overlap[i], fo.overlap[i], 2e-6);
  }
  return test::report("test_aberrations");
}
