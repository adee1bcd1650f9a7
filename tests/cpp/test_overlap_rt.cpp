// RT overlap from C++ against closed forms: point-aperture limit, far-range obstruction limit,
// in-focus defocused detector (Eq. 5), and thread-count independence.
#include <cmath>
#include <vector>

#include "check.hpp"
#include "lidar_overlap/lidar_overlap.hpp"
#include "core/special_functions.hpp"      // internal: the Rice density's exp(-x) I0(x)
#include "geometry/receiver_coupling.hpp"  // internal: the coupling of single scatterers

using namespace lidar_overlap;

int main() {
  LidarSystem s;  // defaults: the paper's Table 1 system at 355 nm
  s.telescope.diameter =
      1e-7;  // point aperture: G = 1 - exp(-2 (alpha z)^2 / w^2), alpha = r_d / f
  std::vector<double> z;
  for (double r = 1.0; r <= 2000.0; r *= 1.5) z.push_back(r);
  const RtOverlap point = overlap_rt(s, z, {1e-8, 0, 4000});
  for (std::size_t i = 0; i < z.size(); ++i) {
    const double w = s.beam.radius(z[i]), az = s.detector.radius / s.telescope.focal_length * z[i];
    test::near("point aperture z=" + std::to_string(z[i]), point.overlap[i],
               -std::expm1(-2 * az * az / (w * w)), 1e-7);
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

  // Off-axis beams: the engine integrates radially with the Rice density where a coupling term has a
  // centre of symmetry, in two dimensions otherwise (an NA cone with a detector offset). An independent Cartesian grid of scatterers
  // over +-4 w, weighted by the irradiance, must agree: the grid rule converges fast on this
  // integrand (measured ~1e-6 at 101 x 101), so 1e-5 at 401 x 401 leaves a wide margin.
  struct Scene {
    Vec2 tilt, beam_offset, detector_offset;
    double r_obs, na;
  };
  const Scene scenes[] = {{{0.3e-3, 0}, {0, 0}, {0, 0}, 0.0, 0.0},       // Rice
                          {{-0.1e-3, 0}, {0.05, 0}, {0, 0}, 0.02, 0.0},  // Rice with obstruction
                          {{0.1e-3, 0}, {0, 0.01}, {0, 0.1e-3}, 0.02, 0.0},    // two Rice terms
                          {{0.1e-3, 0}, {0, 0.01}, {0, 0.1e-3}, 0.02, 0.05}};  // two-dimensional
  for (const Scene& sc : scenes) {
    LidarSystem g;
    g.beam.tilt = sc.tilt;
    g.beam.offset = sc.beam_offset;
    g.detector.offset = sc.detector_offset;
    g.telescope.obstruction_radius = sc.r_obs;
    g.telescope.obstruction_distance = sc.r_obs > 0 ? 0.7 : 0.0;
    if (sc.na > 0) g.detector.numerical_aperture = sc.na;
    for (double zr : {60.0, 150.0, 400.0}) {
      const Receiver rx(g, zr);
      const double w = g.beam.radius(zr);
      const Vec2 c = g.beam.center(zr);
      const int n = 401;
      const double h = 8.0 * w / n;
      double sum = 0.0, weight = 0.0;
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const Vec2 p{c.x - 4.0 * w + (i + 0.5) * h, c.y - 4.0 * w + (j + 0.5) * h};
          const double e = g.beam.irradiance(p, zr);
          sum += e * rx.coupling(p);
          weight += e;
        }
      const double engine = overlap_rt(g, {zr}, {1e-8, 1, 100000}).overlap[0];
      test::near("off-axis scene vs scatterer grid, z=" + std::to_string(zr), engine, sum / weight,
                 1e-5);
    }
  }

  RtOptions one{1e-6, 1, 4000}, two{1e-6, 2, 4000};
  LidarSystem tilted;
  tilted.beam.tilt = {0.2e-3, 0.0};
  const RtOverlap t1 = overlap_rt(tilted, z, one), t2 = overlap_rt(tilted, z, two);
  test::that("thread count does not change results", t1.overlap == t2.overlap);
  // A batch entry is the single-system call, bit for bit, whatever the other entries and the thread count.
  std::vector<LidarSystem> batch;
  std::vector<double> batch_ranges;
  const Vec2 tilts[] = {{0, 0}, {0.2e-3, 0}, {-0.1e-3, 0.05e-3}, {0, 0.3e-3}};
  const Vec2 offsets[] = {{0, 0}, {0.05, 0}, {0, -0.02}, {0.01, 0.01}};
  for (std::size_t k = 0; k < 4; ++k)
    for (double zr : {40.0, 150.0, 900.0}) {
      LidarSystem b;
      b.beam.tilt = tilts[k];
      b.beam.offset = offsets[k];
      if (k == 2) {
        b.telescope.obstruction_radius = 0.02;
        b.telescope.obstruction_distance = 0.7;
      }
      batch.push_back(b);
      batch_ranges.push_back(zr);
    }
  const RtOverlap all = overlap_rt_batch(batch, batch_ranges, {1e-6, 2, 4000});
  bool same = all.overlap.size() == batch.size();
  std::size_t evaluations = 0;
  for (std::size_t i = 0; same && i < batch.size(); ++i) {
    const RtOverlap one = overlap_rt(batch[i], {batch_ranges[i]}, {1e-6, 1, 4000});
    same = one.overlap[0] == all.overlap[i] && one.error_estimate[0] == all.error_estimate[i] &&
           one.converged[0] == all.converged[i];
    evaluations += one.evaluations;
  }
  test::that("batch entries equal single calls bit for bit",
             same && evaluations == all.evaluations);
  test::that("a batch with tilted beams is not axisymmetric", !all.axisymmetric);
  test::that("a batch of axisymmetric systems is",
             overlap_rt_batch({LidarSystem{}}, {300.0}).axisymmetric);
  test::throws("batch sizes differ", [&] { overlap_rt_batch(batch, {100.0}); }, "ranges");
  std::vector<LidarSystem> bad = batch;
  bad[5].telescope.diameter = -1.0;
  test::throws(
      "invalid batch system", [&] { overlap_rt_batch(bad, batch_ranges); },
      "systems[5]: telescope.diameter");
  std::vector<double> short_ranges = batch_ranges;
  short_ranges[7] = 0.0;
  test::throws("invalid batch range", [&] { overlap_rt_batch(batch, short_ranges); }, "ranges[7]");
  // A fibre NA wider than the telescope's holds the whole aperture for every scatterer in the beam: left out of
  // the terms, it gives the system without an NA bit for bit (with a detector offset that would otherwise break
  // the terms' centre of symmetry), at the same cost.
  LidarSystem offset_detector;
  offset_detector.beam.tilt = {0.0, 50e-6};
  offset_detector.detector.offset = {2e-5, 0.0};
  LidarSystem wide_na = offset_detector;
  wide_na.detector.numerical_aperture = 0.22;
  const std::vector<double> na_ranges{20.0, 150.0, 1000.0, 3000.0};
  const RtOverlap with_wide_na = overlap_rt(wide_na, na_ranges),
                  without_na = overlap_rt(offset_detector, na_ranges);
  test::that("wide NA = no NA, bit for bit and at the same cost",
             with_wide_na.overlap == without_na.overlap &&
                 with_wide_na.evaluations == without_na.evaluations);
  LidarSystem narrow_na = offset_detector;
  narrow_na.detector.numerical_aperture = 0.03;
  const RtOverlap with_narrow_na = overlap_rt(narrow_na, na_ranges);
  test::that("a narrow NA still cuts the light",
             with_narrow_na.overlap[3] < 0.9 * without_na.overlap[3]);

  // exp(-x) I0(x) by its Chebyshev series against the standard library (and Hankel's series far out).
  double worst = 0.0;
  for (double x = 0.0; x < 700.0; x += 0.0137)
    worst = std::max(
        worst, std::abs(scaled_bessel_i0(x) / (std::cyl_bessel_i(0.0, x) * std::exp(-x)) - 1.0));
  test::near("scaled_bessel_i0 relative error up to x = 700", worst, 0.0, 4e-15);
  for (double x : {1e4, 1e6, 1e9}) {  // four terms: the fifth is below 1e-16 there
    const double t = 1.0 / (8.0 * x),
                 hankel = (1.0 + t * (1.0 + t * (4.5 + t * 37.5))) / std::sqrt(2.0 * kPi * x);
    test::near("scaled_bessel_i0 far out, x=" + std::to_string(x), scaled_bessel_i0(x) / hankel,
               1.0, 4e-15);
  }
  // exp(-x) I1(x) likewise (relative error down to x near 0, where I1 ~ x / 2), Hankel's series far out.
  worst = 0.0;
  for (double x = 1e-6; x < 700.0; x += 0.0137)
    worst = std::max(
        worst, std::abs(scaled_bessel_i1(x) / (std::cyl_bessel_i(1.0, x) * std::exp(-x)) - 1.0));
  test::near("scaled_bessel_i1 relative error from x = 1e-6 to 700", worst, 0.0, 4e-15);
  test::near("scaled_bessel_i1 at 0", scaled_bessel_i1(0.0), 0.0, 0.0);
  for (double x : {1e4, 1e6, 1e9}) {
    const double t = 1.0 / (8.0 * x),
                 hankel = (1.0 - t * (3.0 + t * (7.5 + t * 52.5))) / std::sqrt(2.0 * kPi * x);
    test::near("scaled_bessel_i1 far out, x=" + std::to_string(x), scaled_bessel_i1(x) / hankel,
               1.0, 4e-15);
  }
  return test::report("test_overlap_rt");
}
