// Invalid input throws std::invalid_argument naming the parameter: a ParameterError that carries the
// parameter, the value and the valid range as data.
#include <cmath>
#include <limits>

#include "check.hpp"
#include "lidar_overlap/lidar_overlap.hpp"

using namespace lidar_overlap;

int main() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  LidarSystem s;
  auto with = [&](auto change) {
    LidarSystem c = s;
    change(c);
    return c;
  };
  test::throws(
      "negative waist", [&] { with([](LidarSystem& c) { c.beam.waist_radius = -1; }).validate(); },
      "beam.waist_radius");
  test::throws(
      "NaN wavelength", [&] { with([&](LidarSystem& c) { c.beam.wavelength = nan; }).validate(); },
      "beam.wavelength");
  test::throws(
      "obstruction >= aperture radius",
      [&] { with([](LidarSystem& c) { c.telescope.obstruction_radius = 0.075; }).validate(); },
      "telescope.obstruction_radius");
  test::throws(
      "detector plane in front of the lens",
      [&] { with([](LidarSystem& c) { c.detector.defocus = -1.0; }).validate(); },
      "detector.defocus");
  test::throws(
      "NA of 1",
      [&] { with([](LidarSystem& c) { c.detector.numerical_aperture = 1.0; }).validate(); },
      "detector.numerical_aperture");
  test::throws("range zero", [&] { overlap_rt(s, {10.0, 0.0}); }, "ranges[1]");
  test::throws("emitter range zero", [&] { emitter_coupling_rt(s, 0.0, {0, 0}); }, "z");
  LidarSystem obs = with([](LidarSystem& c) {
    c.telescope.obstruction_radius = 0.02;
    c.telescope.obstruction_distance = 0.7;
  });
  test::throws(
      "range inside obstruction distance", [&] { overlap_rt(obs, {0.5}); }, "obstruction distance");
  test::throws("tolerance 0", [&] { overlap_rt(s, {10.0}, {0.0, 0, 10}); }, "tolerance");
  test::throws(
      "tolerance below double precision", [&] { overlap_rt(s, {10.0}, {1e-300, 0, 10}); },
      "tolerance");
  test::throws("negative threads", [&] { overlap_rt(s, {10.0}, {1e-4, -1, 10}); }, "threads");
  test::throws("fov <= 0", [] { Detector::from_fov(0.0, 1.0); }, "fov");
  test::throws("negative defocus in Eq. 5", [] { optimal_focus_range(1.0, -1e-3); }, "defocus");
  // The parameter as data: the name the message starts with, the value refused and what was expected.
  auto refusal = [](auto&& call) -> ParameterError {
    try {
      call();
    } catch (const ParameterError& e) {
      return e;
    }
    return ParameterError("nothing refused", "", 0.0, "");
  };
  const ParameterError waist =
      refusal([&] { with([](LidarSystem& c) { c.beam.waist_radius = -1; }).validate(); });
  test::that("waist: parameter", waist.parameter() == "beam.waist_radius");
  test::that("waist: value", waist.value() == -1.0);
  test::that("waist: message starts with it",
             std::string(waist.what()).rfind("beam.waist_radius = -1", 0) == 0);
  test::that("waist: expected in the message",
             !waist.expected().empty() &&
                 std::string(waist.what()).find(waist.expected()) != std::string::npos);
  const ParameterError range = refusal([&] { overlap_rt(s, {10.0, 20.0, -5.0}); });
  test::that("range: parameter names the index",
             range.parameter() == "ranges[2]" && range.value() == -5.0);
  const ParameterError batch = refusal([&] {
    overlap_rt_batch({s, with([&](LidarSystem& c) { c.detector.radius = nan; })}, {10.0, 20.0});
  });
  test::that("batch: parameter names the system",
             batch.parameter() == "systems[1].detector.radius");
  test::that("batch: message names it",
             std::string(batch.what()).rfind("systems[1]: detector.radius", 0) == 0);
  return test::report("test_checks");
}
