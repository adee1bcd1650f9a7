// Alignment maps: every grid point bit for bit the single-system overlap_rt of the same misaligned
// system, whatever the thread count; axis and size errors named.
#include <cmath>
#include <limits>
#include <vector>

#include "check.hpp"
#include "lidar_overlap/lidar_overlap.hpp"

using namespace lidar_overlap;

int main() {
  LidarSystem
      base;  // the paper's Table 1 lidar, with an offset beam so that no point is axisymmetric
  base.beam.offset = {0.05, 0.0};
  const std::vector<double> z{60.0, 250.0, 900.0};
  const std::vector<AlignmentAxis> axes{
      {AlignmentParameter::tilt_x, {-0.2e-3, 0.0, 0.15e-3}},
      {AlignmentParameter::detector_offset_y, {-0.1e-3, 0.05e-3}}};
  const RtOptions options{1e-5, 2, 4000};
  const AlignmentMap map = alignment_map(base, axes, z, options);
  test::that("shape", map.shape == std::vector<std::size_t>{3, 2, 3});
  bool same = map.values.overlap.size() == 18;
  std::size_t evaluations = 0;
  for (std::size_t i = 0; same && i < 3; ++i)
    for (std::size_t j = 0; same && j < 2; ++j) {
      const LidarSystem s = misaligned(misaligned(base, axes[0].parameter, axes[0].values[i]),
                                       axes[1].parameter, axes[1].values[j]);
      const RtOverlap one = overlap_rt(s, z, {1e-5, 1, 4000});
      evaluations += one.evaluations;
      for (std::size_t k = 0; k < z.size(); ++k) {
        const std::size_t e = (i * 2 + j) * z.size() + k;
        same = same && one.overlap[k] == map.values.overlap[e] &&
               one.error_estimate[k] == map.values.error_estimate[e] &&
               one.converged[k] == map.values.converged[e];
      }
    }
  test::that("grid points equal overlap_rt of the misaligned system bit for bit", same);
  test::that("evaluations add up", evaluations == map.values.evaluations);
  test::that("an offset beam is not axisymmetric", !map.values.axisymmetric);

  // Axes that only move the beam trace each distinct beam-centre distance once (a symmetric tilt grid of an
  // obstructed coaxial lidar, -0 among the values): every point still equals its own overlap_rt bit for bit.
  LidarSystem coaxial;
  coaxial.telescope.obstruction_radius = 0.02;
  coaxial.telescope.obstruction_distance = 0.3;
  const std::vector<double> tilts{-3e-4, -1e-4, -0.0, 1e-4, 3e-4}, near_far{40.0, 300.0, 2000.0};
  const AlignmentMap sym = alignment_map(coaxial,
                                         {{AlignmentParameter::tilt_x, tilts},
                                          {AlignmentParameter::beam_offset_y, {-2e-3, 0.0, 2e-3}}},
                                         near_far, {1e-5, 2, 4000});
  bool same_sym = true;
  for (std::size_t i = 0; i < tilts.size(); ++i)
    for (std::size_t j = 0; j < 3; ++j) {
      LidarSystem s = misaligned(coaxial, AlignmentParameter::tilt_x, tilts[i]);
      s = misaligned(s, AlignmentParameter::beam_offset_y, (static_cast<double>(j) - 1.0) * 2e-3);
      const RtOverlap one = overlap_rt(s, near_far, {1e-5, 1, 4000});
      for (std::size_t k = 0; k < near_far.size(); ++k) {
        const std::size_t e = (i * 3 + j) * near_far.size() + k;
        same_sym = same_sym && one.overlap[k] == sym.values.overlap[e] &&
                   one.error_estimate[k] == sym.values.error_estimate[e];
      }
    }
  test::that("mirror-image grid points equal their own overlap_rt bit for bit", same_sym);

  LidarSystem shifted = misaligned(base, AlignmentParameter::defocus, 2e-3);
  test::near("misaligned adds to the system's value", shifted.detector.defocus, 2e-3, 0.0);
  const AlignmentMap one_axis =
      alignment_map(LidarSystem{}, {{AlignmentParameter::defocus, {0.0}}}, {300.0});
  test::that("a map of the aligned Table 1 lidar is axisymmetric", one_axis.values.axisymmetric);
  test::that("one axis: shape (values, ranges)", one_axis.shape == std::vector<std::size_t>{1, 1});

  const double nan = std::numeric_limits<double>::quiet_NaN();
  using P = AlignmentParameter;
  test::throws("no axes", [&] { alignment_map(base, {}, z); }, "axes");
  test::throws(
      "three axes",
      [&] { alignment_map(base, {{P::tilt_x, {0}}, {P::tilt_y, {0}}, {P::defocus, {0}}}, z); },
      "axes");
  test::throws(
      "repeated axis", [&] { alignment_map(base, {{P::tilt_x, {0}}, {P::tilt_x, {1e-4}}}, z); },
      "tilt_x");
  test::throws("empty axis", [&] { alignment_map(base, {{P::tilt_y, {}}}, z); }, "tilt_y");
  test::throws(
      "NaN value", [&] { alignment_map(base, {{P::beam_offset_x, {0.0, nan}}}, z); },
      "beam_offset_x[1]");
  test::throws(
      "unsorted axis", [&] { alignment_map(base, {{P::tilt_x, {1e-4, 0.0}}}, z); }, "tilt_x[1]");
  test::throws(
      "value making an invalid system",
      [&] { alignment_map(base, {{P::tilt_y, {0.0, 1e300}}}, z); }, "tilt_y[1] = 1e+300");
  test::throws(
      "defocus behind the lens", [&] { alignment_map(base, {{P::defocus, {-2.0}}}, z); },
      "defocus[0]");
  AlignmentAxis wide{P::tilt_x, std::vector<double>(70000)},
      tall{P::tilt_y, std::vector<double>(70000)};
  for (std::size_t i = 0; i < 70000; ++i)
    wide.values[i] = tall.values[i] = 1e-9 * static_cast<double>(i);
  test::throws("grid beyond the cap", [&] { alignment_map(base, {wide, tall}, z); }, "axes");
  test::throws("bad range", [&] { alignment_map(base, {{P::tilt_x, {0}}}, {0.0}); }, "ranges[0]");
  test::throws(
      "bad tolerance", [&] { alignment_map(base, {{P::tilt_x, {0}}}, z, {2.0, 0, 4000}); },
      "tolerance");
  test::throws("unknown name", [&] { alignment_parameter_from_name("tilt_z"); }, "tilt_z");
  return test::report("test_alignment_map");
}
