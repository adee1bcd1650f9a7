#include "lidar_overlap/atmosphere/overlap_turbulent.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "lidar_overlap/atmosphere/phase_screen.hpp"
#include "lidar_overlap/atmosphere/turbulent_grid.hpp"
#include "lidar_overlap/core/limits.hpp"
#include "lidar_overlap/fourier/overlap_fo.hpp"
#include "atmosphere/coupling_map.hpp"
#include "atmosphere/phasor.hpp"
#include "atmosphere/return_path.hpp"
#include "atmosphere/scaled_step.hpp"
#include "core/checks.hpp"
#include "core/constants.hpp"
#include "core/entry_checks.hpp"
#include "core/parallel.hpp"
#include "fourier/fft.hpp"
#include "fourier/fo_receiver.hpp"
#include "fourier/overlap_fo_detail.hpp"
#include "fourier/transfer_table.hpp"

namespace lidar_overlap {

namespace {

using detail::CouplingMap;
using detail::ScaledStep;

// A plane the beam passes: a phase screen or a range where the overlap is wanted.
struct Plane {
  double z;
  int screen = -1;  // index into the screens, or -1
  int range = -1;   // index into the ranges, or -1
};

// Both paths (TurbulencePaths::both). Each task carries one pair of screen draws (2p, 2p + 1): both beams and
// both sets of receiver fields through the pair's screens, so that the uncorrelated G (a draw's beam with the
// other draw's receiver) costs no propagation of its own; the call's rows are taken from it. A draw's G
// depends on its screens and its receiver fields' seeds alone: the same in any part and on any thread.
TurbulentOverlap both_paths(const LidarSystem& system, const std::vector<double>& ranges, const TurbulenceOptions& o,
                            int threads, const std::vector<Plane>& planes,
                            const std::vector<std::unique_ptr<ScaledStep>>& steps,
                            const std::vector<std::unique_ptr<PhaseScreenGenerator>>& generators,
                            double dx0, const ScaledStep* last_step) {
  const std::size_t n = o.beam_grid, fields = o.receiver_fields;
  const double lambda = system.beam.wavelength, w0 = system.beam.waist_radius;
  const detail::ReturnPath rx(system, n, dx0, fields);
  const double n2 = double(n) * double(n);
  checks::memory("beam_grid", static_cast<double>(n), turbulent_both_bytes(n, o.screens, fields, threads),
                 "lower beam_grid, receiver_fields or screens");

  TurbulentOverlap out;
  out.overlap.assign(o.realizations, std::vector<double>(ranges.size(), 0.0));
  out.uncorrelated = out.overlap;
  out.receiver_error = out.overlap;
  out.wander_x.assign(o.realizations, 0.0);
  out.wander_y.assign(o.realizations, 0.0);
  out.radius_last.assign(o.realizations, 0.0);
  out.receiver_x.assign(o.realizations, 0.0);
  out.receiver_y.assign(o.realizations, 0.0);
  const std::size_t first = o.first_realization, end = first + o.realizations, p0 = first / 2;
  // The split steps leave each field n^2 times its physical value (their 1 / n^2 waits for the next step).
  const double n4 = n2 * n2, area = rx.aperture_area();
  const std::uint64_t rx_seed = o.seed ^ 0xD1B54A32D192ED03ULL;  // not the screens' streams
  detail::parallel_for((end - 1) / 2 - p0 + 1, threads, [&](std::size_t t) {
    const std::size_t pair = p0 + t;
    std::vector<Field> beams(2, Field::gaussian(lambda, w0, n, dx0));
    std::vector<std::vector<Field>> back(2);
    for (std::size_t c = 0; c < 2; ++c)
      for (std::size_t m = 0; m < fields; ++m) back[c].push_back(rx.pupil_field(rx_seed, 2 * pair + c, m));
    // A screen's exp(i phase) per draw, shared by its beam and receiver fields, applied in the next step's Q1
    // pass (directly if no step follows at once).
    std::array<ComplexBuffer, 2> phasor{ComplexBuffer(n * n), ComplexBuffer(n * n)};
    ComplexBuffer spectrum;
    std::array<std::vector<double>, 2> screens;
    std::vector<double> irradiance(2 * n * n), es(2 * fields), eu(2 * fields);
    bool pending = false;
    for (std::size_t s = 0; s < planes.size(); ++s) {
      const Plane& p = planes[s];
      for (std::size_t c = 0; c < 2; ++c) {
        const Complex* shared = pending ? phasor[c].data() : nullptr;
        auto advance = [&](Field& u) {
          if (steps[s])
            steps[s]->execute(u, nullptr, nullptr, nullptr, shared);
          else if (shared)
            for (std::size_t i = 0; i < n * n; ++i) u.values[i] *= shared[i];
        };
        advance(beams[c]);
        for (Field& v : back[c]) advance(v);
      }
      pending = p.screen >= 0;
      if (pending) {
        const std::uint64_t stream = o.seed ^ (0x9E3779B97F4A7C15ULL * static_cast<std::uint64_t>(p.screen + 1));
        generators[p.screen]->generate_pair(stream, pair, screens, spectrum);
        for (std::size_t c = 0; c < 2; ++c)
          for (std::size_t i = 0; i < n * n; ++i) phasor[c][i] = detail::phasor(screens[c][i]);
      }
      if (p.range < 0) continue;
      // G of each receiver field alone (their mean is the draw's G; their spread over sqrt(M) its random-phase
      // standard error), with this draw's beam and with the other draw's: each beam's irradiance once, then one
      // pass per field index over both draws' fields.
      const double lz = lambda * p.z, factor = lz * lz / (area * n4);
      double e[2] = {0.0, 0.0};
      for (std::size_t c = 0; c < 2; ++c)
        for (std::size_t i = 0; i < n * n; ++i) e[c] += irradiance[c * n * n + i] = std::norm(beams[c].values[i]);
      for (std::size_t m = 0; m < fields; ++m) {
        detail::cancellation_point();  // up to 1000 receiver fields of n^2 samples
        const double* v0 = irradiance.data();
        const double* v1 = v0 + n * n;
        const Complex* b0 = back[0][m].values.data();
        const Complex* b1 = back[1][m].values.data();
        double s0 = 0.0, s1 = 0.0, u0 = 0.0, u1 = 0.0;
        for (std::size_t i = 0; i < n * n; ++i) {
          const double w0 = std::norm(b0[i]), w1 = std::norm(b1[i]);
          s0 += v0[i] * w0;
          u0 += v0[i] * w1;
          s1 += v1[i] * w1;
          u1 += v1[i] * w0;
        }
        es[m] = s0, eu[m] = u0, es[fields + m] = s1, eu[fields + m] = u1;
      }
      for (std::size_t c = 0; c < 2; ++c) {
        const std::size_t k = 2 * pair + c;
        if (k < first || k >= end) continue;
        double sum = 0.0, sum2 = 0.0, unc = 0.0;
        for (std::size_t m = 0; m < fields; ++m) {
          const double g = es[c * fields + m] * factor / e[c];
          sum += g;
          sum2 += g * g;
          unc += eu[c * fields + m] * factor / e[c];
        }
        const double mean = sum / double(fields);
        out.overlap[k - first][p.range] = mean;
        out.uncorrelated[k - first][p.range] = unc / double(fields);
        out.receiver_error[k - first][p.range] =
            fields > 1 ? std::sqrt(std::max(sum2 / double(fields) - mean * mean, 0.0) / double(fields - 1))
                       : std::numeric_limits<double>::quiet_NaN();  // one field shows no spread
      }
    }
    for (std::size_t c = 0; c < 2; ++c) {
      const std::size_t k = 2 * pair + c;
      if (k < first || k >= end) continue;
      if (last_step) last_step->finish(beams[c]);
      const Vec2 centre = beams[c].centroid();
      out.wander_x[k - first] = centre.x;
      out.wander_y[k - first] = centre.y;
      out.radius_last[k - first] = beams[c].beam_radius();
      // The receiver's sensitivity (its fields' summed irradiance; the last step's phase leaves it as it is).
      double power = 0.0, sx = 0.0, sy = 0.0;
      for (const Field& v : back[c]) {
        const double pv = v.power();
        const Vec2 cv = v.centroid();
        power += pv, sx += pv * cv.x, sy += pv * cv.y;
      }
      out.receiver_x[k - first] = power > 0.0 ? sx / power : 0.0;
      out.receiver_y[k - first] = power > 0.0 ? sy / power : 0.0;
    }
  });
  for (const auto& rows : {&out.overlap, &out.uncorrelated})
    for (const std::vector<double>& g : *rows)
      for (std::size_t i = 0; i < g.size(); ++i)
        if (!(g[i] >= 0.0 && std::isfinite(g[i])))
          checks::fail(detail::range_name(i), ranges[i], "a range where the turbulent overlap is finite (internal error)");
  return out;
}

}  // namespace

TurbulentOverlap overlap_fo_turbulent(const LidarSystem& system, const std::vector<double>& ranges,
                                      const Cn2Profile& atmosphere, const TurbulenceOptions& o) {
  system.validate();
  atmosphere.validate();
  const GaussianBeam& beam = system.beam;
  const double lambda = beam.wavelength, w0 = beam.waist_radius;
  if (beam.width_law != WidthLaw::gaussian ||
      (beam.divergence && std::abs(*beam.divergence * kPi * w0 / lambda - 1.0) > 1e-9))
    checks::fail("beam.divergence", beam.divergence.value_or(0.0),
                 "None (a diffraction-limited TEM00 beam with the Gaussian width law) for the turbulent FO path");
  if (o.realizations < 1 || o.realizations > kMaxRealizations)
    checks::fail("realizations", static_cast<double>(o.realizations), "a count from 1 to 1000000");
  // first + realizations <= kMaxRealizations, written so that no sum can wrap (realizations is checked above).
  if (o.first_realization > kMaxRealizations - o.realizations)
    checks::fail("first_realization", static_cast<double>(o.first_realization),
                 "an index from 0 to " + std::to_string(kMaxRealizations - o.realizations) +
                     " (first_realization + realizations <= 1000000)");
  if (o.screens < 1 || o.screens > kMaxScreens) checks::fail("screens", static_cast<double>(o.screens), "a count from 1 to 1000");
  if (o.beam_grid < 32 || o.beam_grid % 2) checks::fail("beam_grid", static_cast<double>(o.beam_grid), "an even size >= 32");
  checks::grid("beam_grid", o.beam_grid, sizeof(Complex), 4);  // at least a field, a screen pair and a map
  if (!(o.beam_window >= 2.0 && o.beam_window <= static_cast<double>(o.beam_grid)))
    checks::fail("beam_window", o.beam_window, "a window from 2 to beam_grid long-term beam radii");
  if (o.max_spectrum_grid < 32 || o.max_spectrum_grid > kMaxGridSide)
    checks::fail("max_spectrum_grid", static_cast<double>(o.max_spectrum_grid), "a size from 32 to 65536");
  const bool both = o.paths == TurbulencePaths::both;
  if (o.paths != TurbulencePaths::transmit && !both) checks::fail("paths", static_cast<double>(o.paths), "transmit or both");
  if (both && (o.receiver_fields < 1 || o.receiver_fields > kMaxReceiverFields))
    checks::fail("receiver_fields", static_cast<double>(o.receiver_fields), "a count from 1 to 1000");
  if (both && system.detector.numerical_aperture)
    checks::fail("detector.numerical_aperture", *system.detector.numerical_aperture,
                 "none (a fibre's NA is not modelled on the turbulent return path) for paths = both");
  const int threads = detail::checked_threads_and_ranges(system, ranges, o.threads);
  if (ranges.empty()) return {};
  const double z_max = *std::max_element(ranges.begin(), ranges.end());
  const std::size_t n = o.beam_grid;

  // Each plane's grid (atmosphere/turbulent_grid.hpp): the beam's window and, on both paths, the receiver's
  // light; on both paths every plane's spacing must sample the receiver's light, or it aliases.
  auto spacing_at = [&](double z) { return turbulent_window(system, atmosphere, o.beam_window, o.paths, z) / n; };
  if (both) {
    const std::size_t need = turbulent_grid(system, ranges, atmosphere, o).min_beam_grid;
    if (n < need)
      checks::fail("beam_grid", static_cast<double>(n),
                   "an even size >= " + std::to_string(need) +
                       " for paths = both: every plane's grid must sample the receiver's field of view and the eddies' "
                       "spread (lambda / r0)");
  }
  const std::vector<ScreenPlacement> placements = atmosphere.place_screens(lambda, z_max, o.screens);
  std::vector<Plane> planes;
  for (std::size_t j = 0; j < placements.size(); ++j) planes.push_back({placements[j].range, static_cast<int>(j), -1});
  for (std::size_t i = 0; i < ranges.size(); ++i) planes.push_back({ranges[i], -1, static_cast<int>(i)});
  std::stable_sort(planes.begin(), planes.end(), [](const Plane& a, const Plane& b) { return a.z < b.z; });

  // Shared, made once: one screen generator and one scaled split step per plane (the grid spacing grows
  // with the beam), the receivers and spectrum grids per range.
  std::vector<std::unique_ptr<PhaseScreenGenerator>> generators(placements.size());
  std::vector<std::unique_ptr<ScaledStep>> steps;
  std::vector<double> range_spacing(ranges.size());
  std::vector<FoReceiver> receivers;
  std::vector<std::size_t> grids(ranges.size());
  std::vector<std::unique_ptr<CouplingMap>> maps(ranges.size());
  double z_prev = 0.0, dx_prev = spacing_at(0.0);
  const ScaledStep* last_step = nullptr;
  for (const Plane& p : planes) {
    const double dx = std::max(dx_prev, spacing_at(p.z));
    if (p.z > z_prev) {
      steps.push_back(std::make_unique<ScaledStep>(n, dx_prev, dx, p.z - z_prev, lambda, last_step));
      last_step = steps.back().get();
    } else {
      steps.push_back(nullptr);
    }
    if (p.screen >= 0)
      generators[p.screen] = std::make_unique<PhaseScreenGenerator>(n, dx, placements[p.screen].r0, atmosphere.outer_scale,
                                                                    atmosphere.inner_scale);
    if (p.range >= 0) range_spacing[p.range] = dx;
    z_prev = p.z;
    dx_prev = dx;
  }
  auto described = [&](TurbulentOverlap out) {
    for (std::size_t j = 0; j < placements.size(); ++j) {
      out.screen_range.push_back(placements[j].range);
      out.screen_spacing.push_back(generators[j]->spacing());
      out.screen_r0.push_back(placements[j].r0);
    }
    return out;
  };
  if (both) return described(both_paths(system, ranges, o, threads, planes, steps, generators, spacing_at(0.0),
                                        last_step));
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    receivers.emplace_back(system, ranges[i], detail::range_name(i));
    const double radius = 2.84 * (atmosphere.long_term_radius(w0, lambda, ranges[i]) +
                                  3.0 * std::sqrt(atmosphere.beam_wander_variance(w0, lambda, ranges[i])));
    // Tails to 1e-4 of G: far below the spread between realisations, at a quarter of the grid of 1e-6.
    grids[i] = detail::spectrum_grid(system, receivers[i], ranges[i], range_spacing[i], radius, n,
                                     o.max_spectrum_grid, i, 1e-4);
  }
  // Coupling maps (one n x n table per range), screen generators (a spectrum each) and per-thread fields and
  // map-building buffers, before any of it is allocated.
  double np_max = 0.0;
  for (std::size_t g : grids) np_max = std::max(np_max, static_cast<double>(g));
  const double n2 = double(n) * double(n);
  checks::memory("beam_grid", static_cast<double>(n),
                 8.0 * n2 * double(ranges.size()) + 16.0 * n2 * double(o.screens) +
                     double(threads) * (16.0 * 4.0 * n2 + CouplingMap::workspace(n, static_cast<std::size_t>(np_max))),
                 "lower beam_grid, screens or the number of ranges");
  detail::parallel_for(ranges.size(), threads, [&](std::size_t i) {
    maps[i] = std::make_unique<CouplingMap>(system, receivers[i], ranges[i], range_spacing[i], n, grids[i]);
  });

  TurbulentOverlap out;
  out.overlap.assign(o.realizations, std::vector<double>(ranges.size(), 0.0));
  out.wander_x.assign(o.realizations, 0.0);
  out.wander_y.assign(o.realizations, 0.0);
  out.radius_last.assign(o.realizations, 0.0);
  // Screen j of realisation k (k counted from the run's start: first_realization + row) is element k % 2 of
  // pair k / 2 of screen j's stream (the seed mixed with j): one FFT makes both. With enough realisations to
  // keep every thread busy, each task carries the realisations of one pair side by side and uses both
  // screens; a part that starts or ends inside a pair takes its one member of it. Each realisation's field
  // sees only its own screens, so its G is the same in any part and on any thread.
  const std::size_t first = o.first_realization, end = first + o.realizations;
  const bool by_pairs = o.realizations >= 2 * static_cast<std::size_t>(threads);
  const std::size_t tasks = by_pairs ? (end - 1) / 2 - first / 2 + 1 : o.realizations;
  detail::parallel_for(tasks, threads, [&](std::size_t t) {
    const std::size_t k0 = by_pairs ? std::max(first, 2 * (first / 2 + t)) : first + t;
    const std::size_t count = by_pairs ? std::min(end, 2 * (first / 2 + t) + 2) - k0 : 1;
    std::vector<Field> fields(count, Field::gaussian(lambda, w0, n, spacing_at(0.0)));
    // A screen is applied in the pass of the next step's Q1, and a range's sums taken in the pass that ends
    // its step: no pass of their own. Phases do not change the irradiance the outputs read, so a screen
    // with no step after it is left unapplied.
    std::array<std::vector<double>, 2> screen_pair;  // the pair's screens at one plane, then the next plane's
    ComplexBuffer spectrum;                         // their transform's workspace
    bool pending = false;
    std::vector<double> row_sums(2 * n);
    for (std::size_t s = 0; s < planes.size(); ++s) {
      const Plane& p = planes[s];
      const CouplingMap* map = p.range >= 0 ? maps[p.range].get() : nullptr;
      for (std::size_t c = 0; c < count; ++c) {
        const std::vector<double>& screen = screen_pair[(k0 + c) % 2];
        if (steps[s])
          steps[s]->execute(fields[c], pending ? screen.data() : nullptr, map ? map->values() : nullptr, row_sums.data());
        else if (pending)
          apply_phase_screen(fields[c], screen);
        if (map) out.overlap[k0 - first + c][p.range] = steps[s] ? map->overlap(row_sums) : map->overlap(fields[c]);
      }
      pending = p.screen >= 0;
      if (pending) {
        const std::uint64_t stream = o.seed ^ (0x9E3779B97F4A7C15ULL * static_cast<std::uint64_t>(p.screen + 1));
        generators[p.screen]->generate_pair(stream, k0 / 2, screen_pair, spectrum);
      }
    }
    for (std::size_t c = 0; c < count; ++c) {
      if (last_step) last_step->finish(fields[c]);
      const Vec2 centre = fields[c].centroid();
      out.wander_x[k0 - first + c] = centre.x;
      out.wander_y[k0 - first + c] = centre.y;
      out.radius_last[k0 - first + c] = fields[c].beam_radius();
    }
  });
  for (std::vector<double>& g : out.overlap) checks::overlap_values(g, ranges, detail::kFoOverlapSlack, "overlap_fo_turbulent");
  return described(std::move(out));
}

}  // namespace lidar_overlap
