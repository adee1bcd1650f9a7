#include "lidar_overlap/atmosphere/turbulent_grid.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/checks.hpp"
#include "core/entry_checks.hpp"

namespace lidar_overlap {

namespace {

// Samples per detector radius of the return path's random-phase fields (atmosphere/return_path.hpp): the
// pupil's spacing must resolve the field of view's plane waves with the margin of one of them.
constexpr double kDetectorSamples = 8.0;

// The least even size >= x (and >= 32, the turbulent path's floor), saturating instead of wrapping.
std::size_t even_at_least(double x) {
  const double n = 2.0 * std::ceil(0.5 * std::max(x, 32.0));
  return checks::saturate(n);
}

}  // namespace

double turbulent_seeing(const LidarSystem& system, const Cn2Profile& atmosphere, double z) {
  const double lambda = system.beam.wavelength;
  const double r0 = z > 0.0 ? atmosphere.fried_parameter_plane(lambda, z) : 0.0;
  return std::isfinite(r0) && r0 > 0.0 ? lambda / r0 : 0.0;
}

double receiver_max_angle(const LidarSystem& system) {
  const Telescope& t = system.telescope;
  const double d = t.focal_length + system.detector.defocus;
  return (system.detector.radius + norm(system.detector.offset)) / d +
         0.5 * t.diameter * std::abs(1.0 / t.focal_length - 1.0 / d) + norm(system.beam.tilt);
}

double turbulent_window(const LidarSystem& system, const Cn2Profile& atmosphere, double beam_window,
                        TurbulencePaths paths, double z) {
  const GaussianBeam& beam = system.beam;
  const double lambda = beam.wavelength, w0 = beam.waist_radius;
  const double beam_side =
      z == 0.0 ? beam_window * w0
               : beam_window * atmosphere.long_term_radius(w0, lambda, z) +
                     8.0 * std::sqrt(atmosphere.beam_wander_variance(w0, lambda, z));
  if (paths != TurbulencePaths::both) return beam_side;
  const double foot =
      0.5 * system.telescope.diameter *
          std::abs(1.0 - z * (1.0 / system.telescope.focal_length -
                              1.0 / (system.telescope.focal_length + system.detector.defocus))) +
      (system.detector.radius + norm(system.detector.offset)) * z /
          (system.telescope.focal_length + system.detector.defocus);
  return std::max(beam_side, 2.0 * (norm(beam.center(z)) + 1.25 * foot +
                                    2.0 * z * turbulent_seeing(system, atmosphere, z)));
}

TurbulentGrid turbulent_grid(const LidarSystem& system, const std::vector<double>& ranges,
                             const Cn2Profile& atmosphere, const TurbulenceOptions& o) {
  system.validate();
  atmosphere.validate();
  detail::checked_threads_and_ranges(system, ranges, 1);
  if (o.screens < 1 || o.screens > kMaxScreens)
    checks::fail("screens", static_cast<double>(o.screens), "a count from 1 to 1000");
  if (!(o.beam_window >= 2.0 && std::isfinite(o.beam_window)))
    checks::fail("beam_window", o.beam_window, "a window of at least 2 long-term beam radii");
  if (o.paths != TurbulencePaths::transmit && o.paths != TurbulencePaths::both)
    checks::fail("paths", static_cast<double>(o.paths), "transmit or both");
  TurbulentGrid out;
  if (ranges.empty()) return out;
  const double lambda = system.beam.wavelength,
               z_max = *std::max_element(ranges.begin(), ranges.end());
  // The planes in overlap_fo_turbulent's order: screens, then ranges, stably sorted by range.
  std::vector<std::pair<double, bool>> planes;  // (range, a screen's plane)
  for (const ScreenPlacement& p : atmosphere.place_screens(lambda, z_max, o.screens))
    planes.push_back({p.range, true});
  for (double zi : ranges) planes.push_back({zi, false});
  std::stable_sort(planes.begin(), planes.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<double> z;
  for (const auto& p : planes) z.push_back(p.first);
  out.pupil_window = turbulent_window(system, atmosphere, o.beam_window, o.paths, 0.0);
  out.plane_range = z;
  out.window.assign(z.size(), 0.0);
  // Segments run from a screen (or the transmitter) to the next screen (or the last plane); in each the side
  // grows linearly with range from the start's (a cone: atmosphere/scaled_step.hpp), to the least end side
  // that keeps every plane's side at or above its window and the start's.
  double z_a = 0.0, side_a = out.pupil_window;
  for (std::size_t p = 0; p < z.size();) {
    if (z[p] <=
        z_a) {  // a range at the segment's start (after the screen there): the screen's side
      out.window[p++] = side_a;
      continue;
    }
    std::size_t e = p;
    while (e + 1 < z.size() && !planes[e].second) ++e;
    const double span = z[e] - z_a;
    double side_b =
        std::max(side_a, turbulent_window(system, atmosphere, o.beam_window, o.paths, z[e]));
    for (std::size_t q = p; q < e; ++q)
      side_b = std::max(
          side_b,
          side_a + (turbulent_window(system, atmosphere, o.beam_window, o.paths, z[q]) - side_a) *
                       span / (z[q] - z_a));
    for (std::size_t q = p; q < e; ++q)
      out.window[q] = side_a + (side_b - side_a) * (z[q] - z_a) / span;
    out.window[e] = side_b;
    z_a = z[e], side_a = side_b, p = e + 1;
  }
  if (o.paths != TurbulencePaths::both) return out;
  const double angle = receiver_max_angle(system),
               d = system.telescope.focal_length + system.detector.defocus;
  // The pupil resolves the field of view's plane waves, (|offset| + radius) / d < lambda / (2 spacing) (1 -
  // 1 / 8), strictly; each plane samples the receiver's light, angle + lambda / r0 <= lambda / (2 spacing).
  const double fov = (system.detector.radius + norm(system.detector.offset)) / d;
  double need =
      std::floor(2.0 * out.pupil_window * fov / (lambda * (1.0 - 1.0 / kDetectorSamples))) + 1.0;
  for (std::size_t p = 0; p < z.size(); ++p)
    need = std::max(
        need, out.window[p] * 2.0 * (angle + turbulent_seeing(system, atmosphere, z[p])) / lambda);
  out.min_beam_grid = even_at_least(need);
  return out;
}

double turbulent_both_bytes(std::size_t beam_grid, std::size_t screens, std::size_t receiver_fields,
                            int threads) {
  const double n2 = double(beam_grid) * double(beam_grid);
  return 16.0 * n2 * double(screens) +
         16.0 * double(threads) * n2 * (2.0 * double(receiver_fields) + 8.0);
}

}  // namespace lidar_overlap
