#include "lidar_overlap/atmosphere/overlap_turbulent.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "lidar_overlap/atmosphere/phase_screen.hpp"
#include "lidar_overlap/atmosphere/turbulent_grid.hpp"
#include "lidar_overlap/core/limits.hpp"
#include "atmosphere/segment_plan.hpp"
#include "atmosphere/turbulent_paths.hpp"
#include "core/checks.hpp"
#include "core/constants.hpp"
#include "core/entry_checks.hpp"
#include "fourier/overlap_fo_detail.hpp"

namespace lidar_overlap {

namespace detail {

// The rows of a part of `realizations` draws at `n_ranges` ranges, zero until computed.
TurbulentOverlap zero_rows(std::size_t realizations, std::size_t n_ranges, bool both) {
  TurbulentOverlap out;
  out.overlap.assign(realizations, std::vector<double>(n_ranges, 0.0));
  if (both) {
    out.uncorrelated = out.overlap;
    out.receiver_error = out.overlap;
  }
  out.wander_x.assign(realizations, 0.0);
  out.wander_y.assign(realizations, 0.0);
  out.radius_last.assign(realizations, 0.0);
  if (both) {
    out.receiver_x.assign(realizations, 0.0);
    out.receiver_y.assign(realizations, 0.0);
  }
  return out;
}

}  // namespace detail

namespace {

using detail::Plane;
using detail::TurbulentPlan;

// The options, system and profile the turbulent FO path accepts, or an error naming the first that is not.
void check_turbulent_options(const LidarSystem& system, const Cn2Profile& atmosphere,
                             const TurbulenceOptions& o) {
  system.validate();
  atmosphere.validate();
  const GaussianBeam& beam = system.beam;
  const double lambda = beam.wavelength, w0 = beam.waist_radius;
  if (beam.width_law != WidthLaw::gaussian ||
      (beam.divergence && std::abs(*beam.divergence * kPi * w0 / lambda - 1.0) > 1e-9))
    checks::fail(
        "beam.divergence", beam.divergence.value_or(0.0),
        "None (a diffraction-limited TEM00 beam with the Gaussian width law) for the turbulent FO path");
  if (o.realizations < 1 || o.realizations > kMaxRealizations)
    checks::fail("realizations", static_cast<double>(o.realizations), "a count from 1 to 1000000");
  // first + realizations <= kMaxRealizations, written so that no sum can wrap (realizations is checked above).
  if (o.first_realization > kMaxRealizations - o.realizations)
    checks::fail("first_realization", static_cast<double>(o.first_realization),
                 "an index from 0 to " + std::to_string(kMaxRealizations - o.realizations) +
                     " (first_realization + realizations <= 1000000)");
  if (o.screens < 1 || o.screens > kMaxScreens)
    checks::fail("screens", static_cast<double>(o.screens), "a count from 1 to 1000");
  if (o.beam_grid < 32 || o.beam_grid % 2)
    checks::fail("beam_grid", static_cast<double>(o.beam_grid), "an even size >= 32");
  checks::grid("beam_grid", o.beam_grid, sizeof(Complex),
               4);  // at least a field, a screen pair and a map
  if (!(o.beam_window >= 2.0 && o.beam_window <= static_cast<double>(o.beam_grid)))
    checks::fail("beam_window", o.beam_window, "a window from 2 to beam_grid long-term beam radii");
  if (o.max_spectrum_grid < 32 || o.max_spectrum_grid > kMaxGridSide)
    checks::fail("max_spectrum_grid", static_cast<double>(o.max_spectrum_grid),
                 "a size from 32 to 65536");
  const bool both = o.paths == TurbulencePaths::both;
  if (o.paths != TurbulencePaths::transmit && !both)
    checks::fail("paths", static_cast<double>(o.paths), "transmit or both");
  if (both && (o.receiver_fields < 1 || o.receiver_fields > kMaxReceiverFields))
    checks::fail("receiver_fields", static_cast<double>(o.receiver_fields),
                 "a count from 1 to 1000");
  if (both && system.detector.numerical_aperture)
    checks::fail(
        "detector.numerical_aperture", *system.detector.numerical_aperture,
        "none (a fibre's NA is not modelled on the turbulent return path) for paths = both");
}

// The screens' draws: one generator per screen at its plane's spacing (and each range's spacing, into
// range_spacing).
std::vector<std::unique_ptr<PhaseScreenGenerator>> screen_generators(
    const TurbulentPlan& plan, const std::vector<ScreenPlacement>& placements,
    const Cn2Profile& atmosphere, std::size_t n, std::vector<double>& range_spacing) {
  std::vector<std::unique_ptr<PhaseScreenGenerator>> generators(placements.size());
  for (std::size_t q = 0; q < plan.planes.size(); ++q) {
    const Plane& p = plan.planes[q];
    if (p.screen >= 0)
      generators[p.screen] =
          std::make_unique<PhaseScreenGenerator>(n, plan.spacing[q], placements[p.screen].r0,
                                                 atmosphere.outer_scale, atmosphere.inner_scale);
    if (p.range >= 0) range_spacing[p.range] = plan.spacing[q];
  }
  return generators;
}

}  // namespace

TurbulentOverlap overlap_fo_turbulent(const LidarSystem& system, const std::vector<double>& ranges,
                                      const Cn2Profile& atmosphere, const TurbulenceOptions& o) {
  check_turbulent_options(system, atmosphere, o);
  const bool both = o.paths == TurbulencePaths::both;
  const int threads = detail::checked_threads_and_ranges(system, ranges, o.threads);
  if (ranges.empty()) return {};
  const double lambda = system.beam.wavelength;
  const double z_max = *std::max_element(ranges.begin(), ranges.end());
  const std::size_t n = o.beam_grid;

  // Each plane's grid (atmosphere/turbulent_grid.hpp): the beam's window and, on both paths, the receiver's
  // light; on both paths every plane's spacing must sample the receiver's light, or it aliases.
  const TurbulentGrid grid = turbulent_grid(system, ranges, atmosphere, o);
  if (both && n < grid.min_beam_grid)
    checks::fail(
        "beam_grid", static_cast<double>(n),
        "an even size >= " + std::to_string(grid.min_beam_grid) +
            " for paths = both: every plane's grid must sample the receiver's field of view and the eddies' "
            "spread (lambda / r0)");
  const std::vector<ScreenPlacement> placements =
      atmosphere.place_screens(lambda, z_max, o.screens);
  std::vector<double> screen_ranges;
  for (const ScreenPlacement& p : placements) screen_ranges.push_back(p.range);
  const TurbulentPlan plan =
      detail::plan_propagation(screen_ranges, ranges, grid.window, grid.pupil_window, n, lambda);
  const double dx0 = grid.pupil_window / static_cast<double>(n);
  std::vector<double> range_spacing(ranges.size());
  const auto generators = screen_generators(plan, placements, atmosphere, n, range_spacing);

  TurbulentOverlap out =
      both ? detail::both_paths(system, ranges, o, threads, plan, generators, dx0)
           : detail::transmit_path(
                 system, ranges, o, threads, plan, generators,
                 detail::coupling_maps(system, ranges, atmosphere, o, threads, range_spacing), dx0);
  for (std::size_t j = 0; j < placements.size(); ++j) {
    out.screen_range.push_back(placements[j].range);
    out.screen_spacing.push_back(generators[j]->spacing());
    out.screen_r0.push_back(placements[j].r0);
  }
  return out;
}

}  // namespace lidar_overlap
