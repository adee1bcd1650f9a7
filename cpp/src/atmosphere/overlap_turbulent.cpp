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
#include "atmosphere/segment_plan.hpp"
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
using detail::Plane;
using detail::TurbulentPlan;
using detail::Segment;

// The receiver fields' seeds are drawn from the run's seed mixed with this: no screen's stream.
constexpr std::uint64_t kReceiverSeedMask = 0xD1B54A32D192ED03ULL;

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

// One task of both_paths: the draws 2 pair and 2 pair + 1, each a beam and `fields` receiver fields carried
// through the pair's screens, and the buffers their couplings are summed in.
struct DrawPair {
  DrawPair(const detail::ReturnPath& rx, std::uint64_t rx_seed, std::size_t pair,
           std::size_t fields, double lambda, double w0, std::size_t n, double dx0)
      : beams(2, Field::gaussian(lambda, w0, n, dx0)),
        back(2),
        phasor{ComplexBuffer(n * n), ComplexBuffer(n * n)},
        work(beams[0]),
        irradiance(2 * n * n),
        lines(2 * n),
        es(2 * fields),
        eu(2 * fields) {
    for (std::size_t c = 0; c < 2; ++c)
      for (std::size_t m = 0; m < fields; ++m)
        back[c].push_back(rx.pupil_field(rx_seed, 2 * pair + c, m));
  }

  // Every field from the segment's start: through its screen (one exp(i phase) per draw, shared by its beam and
  // receiver fields), or none for the transmitter's.
  void depart(const Segment& s,
              const std::vector<std::unique_ptr<PhaseScreenGenerator>>& generators,
              std::uint64_t seed, std::size_t pair) {
    const std::size_t n2 = irradiance.size() / 2;
    if (s.screen >= 0) {
      generators[s.screen]->generate_pair(screen_stream(seed, s.screen), pair, screens, spectrum);
      for (std::size_t c = 0; c < 2; ++c) detail::phasors(screens[c].data(), phasor[c].data(), n2);
    }
    for (std::size_t c = 0; c < 2; ++c) {
      const Complex* shared = s.screen >= 0 ? phasor[c].data() : nullptr;
      s.departure.execute(beams[c], nullptr, nullptr, shared);
      for (Field& v : back[c]) s.departure.execute(v, nullptr, nullptr, shared);
    }
  }

  // A field at `arrival`'s plane, read by columns; at the segment's end (`last`) also written back (it goes on).
  template <class Read>
  void reach(const detail::Arrival& arrival, bool last, Field& u, Read&& read) {
    arrival.execute(u, last ? u : work, last ? &u : nullptr, read);
  }

  // Every field carried to the segment's end through a plane where no G is wanted.
  void pass(const detail::Arrival& arrival) {
    for (std::size_t c = 0; c < 2; ++c) {
      reach(arrival, true, beams[c], [](std::size_t, const Complex*) {});
      for (Field& v : back[c]) reach(arrival, true, v, [](std::size_t, const Complex*) {});
    }
  }

  // G of each receiver field alone (their mean is the draw's G; their spread over sqrt(M) its random-phase
  // standard error), with this draw's beam and with the other draw's: each beam's irradiance once (by columns),
  // then each receiver field's sums with both, column by column as it arrives. Fills power, es and eu.
  void couple(const detail::Arrival& arrival, bool last) {
    const std::size_t n = lines.size() / 2, fields = es.size() / 2;
    power[0] = power[1] = 0.0;
    for (std::size_t c = 0; c < 2; ++c) {
      double* v = irradiance.data() + c * n * n;
      reach(arrival, last, beams[c], [&](std::size_t ix, const Complex* column) {
        double sum = 0.0;
        for (std::size_t iy = 0; iy < n; ++iy) sum += v[ix * n + iy] = std::norm(column[iy]);
        lines[ix] = sum;
      });
      for (std::size_t ix = 0; ix < n; ++ix) power[c] += lines[ix];
    }
    for (std::size_t c = 0; c < 2; ++c)
      for (std::size_t m = 0; m < fields; ++m) {
        const double* own = irradiance.data() + c * n * n;
        const double* other = irradiance.data() + (1 - c) * n * n;
        reach(arrival, last, back[c][m], [&](std::size_t ix, const Complex* column) {
          double so = 0.0, su = 0.0;
          for (std::size_t iy = 0; iy < n; ++iy) {
            const double w = std::norm(column[iy]);
            so += own[ix * n + iy] * w;
            su += other[ix * n + iy] * w;
          }
          lines[2 * ix] = so, lines[2 * ix + 1] = su;
        });
        double so = 0.0, su = 0.0;
        for (std::size_t ix = 0; ix < n; ++ix) so += lines[2 * ix], su += lines[2 * ix + 1];
        es[c * fields + m] = so, eu[(1 - c) * fields + m] = su;
      }
  }

  // Draw c's G at `range` from couple()'s sums (`factor` = (lambda z)^2 / aperture area) into row `row` of out.
  void store(TurbulentOverlap& out, std::size_t row, std::size_t c, int range,
             double factor) const {
    const std::size_t fields = es.size() / 2;
    double sum = 0.0, sum2 = 0.0, unc = 0.0;
    for (std::size_t m = 0; m < fields; ++m) {
      const double g = es[c * fields + m] * factor / power[c];
      sum += g;
      sum2 += g * g;
      unc += eu[c * fields + m] * factor / power[c];
    }
    const double mean = sum / double(fields);
    out.overlap[row][range] = mean;
    out.uncorrelated[row][range] = unc / double(fields);
    out.receiver_error[row][range] =
        fields > 1
            ? std::sqrt(std::max(sum2 / double(fields) - mean * mean, 0.0) / double(fields - 1))
            : std::numeric_limits<double>::quiet_NaN();  // one field shows no spread
  }

  // Draw c's beam centroid and radius and the receiver's sensitivity centroid (its fields' summed irradiance) at
  // the last plane, into row `row` of out.
  void store_ends(TurbulentOverlap& out, std::size_t row, std::size_t c) const {
    const Vec2 centre = beams[c].centroid();
    out.wander_x[row] = centre.x;
    out.wander_y[row] = centre.y;
    out.radius_last[row] = beams[c].beam_radius();
    double total = 0.0, sx = 0.0, sy = 0.0;
    for (const Field& v : back[c]) {
      const double pv = v.power();
      const Vec2 cv = v.centroid();
      total += pv, sx += pv * cv.x, sy += pv * cv.y;
    }
    out.receiver_x[row] = total > 0.0 ? sx / total : 0.0;
    out.receiver_y[row] = total > 0.0 ? sy / total : 0.0;
  }

  std::vector<Field> beams;
  std::vector<std::vector<Field>> back;  // each draw's receiver fields
  std::array<ComplexBuffer, 2> phasor;   // a screen's exp(i phase) per draw
  ComplexBuffer spectrum;
  std::array<std::vector<double>, 2> screens;
  Field work;
  std::vector<double> irradiance, lines, es, eu;  // by columns
  double power[2] = {0.0, 0.0};                   // each beam's power at the plane
};

// Every G of both paths finite and >= 0, or an internal error naming the range.
void check_both_rows(const TurbulentOverlap& out, const std::vector<double>& ranges) {
  for (const auto& rows : {&out.overlap, &out.uncorrelated})
    for (const std::vector<double>& g : *rows)
      for (std::size_t i = 0; i < g.size(); ++i)
        if (!(g[i] >= 0.0 && std::isfinite(g[i])))
          checks::fail(detail::range_name(i), ranges[i],
                       "a range where the turbulent overlap is finite (internal error)");
}

// Both paths (TurbulencePaths::both). Each task carries one pair of screen draws (2p, 2p + 1): both beams and
// both sets of receiver fields through the pair's screens, so that the uncorrelated G (a draw's beam with the
// other draw's receiver) costs no propagation of its own; the call's rows are taken from it. A draw's G
// depends on its screens and its receiver fields' seeds alone: the same in any part and on any thread.
TurbulentOverlap both_paths(const LidarSystem& system, const std::vector<double>& ranges,
                            const TurbulenceOptions& o, int threads, const TurbulentPlan& plan,
                            const std::vector<std::unique_ptr<PhaseScreenGenerator>>& generators,
                            double dx0) {
  const std::size_t n = o.beam_grid, fields = o.receiver_fields;
  const double lambda = system.beam.wavelength, w0 = system.beam.waist_radius;
  const detail::ReturnPath rx(system, n, dx0, fields);
  checks::memory("beam_grid", static_cast<double>(n),
                 turbulent_both_bytes(n, o.screens, fields, threads),
                 "lower beam_grid, receiver_fields or screens");

  TurbulentOverlap out = zero_rows(o.realizations, ranges.size(), true);
  const std::size_t first = o.first_realization, end = first + o.realizations, p0 = first / 2;
  const double area = rx.aperture_area();
  const std::uint64_t rx_seed = o.seed ^ kReceiverSeedMask;
  detail::parallel_for((end - 1) / 2 - p0 + 1, threads, [&](std::size_t t) {
    const std::size_t pair = p0 + t;
    auto in_part = [&](std::size_t c) { return 2 * pair + c >= first && 2 * pair + c < end; };
    DrawPair draws(rx, rx_seed, pair, fields, lambda, w0, n, dx0);
    for (const Segment& s : plan.segments) {
      draws.depart(s, generators, o.seed, pair);
      for (std::size_t j = 0; j < s.targets.size(); ++j) {
        const Plane& p = plan.planes[s.targets[j]];
        const bool last =
            j + 1 == s.targets.size();  // the segment's end: each field arrives in place
        if (p.range < 0) {
          if (last) draws.pass(s.arrivals[j]);
          continue;
        }
        draws.couple(s.arrivals[j], last);
        const double lz = lambda * p.z, factor = lz * lz / area;
        for (std::size_t c = 0; c < 2; ++c)
          if (in_part(c)) draws.store(out, 2 * pair + c - first, c, p.range, factor);
      }
    }
    for (std::size_t c = 0; c < 2; ++c)
      if (in_part(c)) draws.store_ends(out, 2 * pair + c - first, c);
  });
  check_both_rows(out, ranges);
  return out;
}

// One segment's arrivals for a field whose spectrum u holds (after the segment's departure): each range's G
// through its coupling map, handed to read(range, G); other planes are passed by, but the segment's end,
// which u itself reaches.
template <class Read>
void arrive(const Segment& s, const TurbulentPlan& plan,
            const std::vector<std::unique_ptr<CouplingMap>>& maps, Field& u, Field& work,
            std::vector<double>& column_sums, Read&& read) {
  const std::size_t n = u.n;
  for (std::size_t j = 0; j < s.targets.size(); ++j) {
    const Plane& p = plan.planes[s.targets[j]];
    const bool last = j + 1 == s.targets.size();
    if (p.range >= 0) {
      const double* map = maps[p.range]->values();
      s.arrivals[j].execute(u, last ? u : work, last ? &u : nullptr,
                            [&](std::size_t ix, const Complex* column) {
                              detail::map_column_sums(ix, column, n, map, column_sums.data());
                            });
      read(static_cast<std::size_t>(p.range), maps[p.range]->overlap(column_sums));
    } else if (last) {
      s.arrivals[j].execute(u, u, &u, [](std::size_t, const Complex*) {});
    }
  }
}

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

// The coupling map of each range (one n x n table each) for the transmit-only path, after its memory is checked:
// the maps, the screen generators (a spectrum each), the field at the first screen and per thread two fields, a
// work field, a screen pair, its spectrum and map-building buffers, before any of it is allocated.
std::vector<std::unique_ptr<CouplingMap>> coupling_maps(const LidarSystem& system,
                                                        const std::vector<double>& ranges,
                                                        const Cn2Profile& atmosphere,
                                                        const TurbulenceOptions& o, int threads,
                                                        const std::vector<double>& range_spacing) {
  const GaussianBeam& beam = system.beam;
  const double lambda = beam.wavelength, w0 = beam.waist_radius;
  const std::size_t n = o.beam_grid;
  std::vector<FoReceiver> receivers;
  std::vector<std::size_t> grids(ranges.size());
  std::vector<std::unique_ptr<CouplingMap>> maps(ranges.size());
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    receivers.emplace_back(system, ranges[i], detail::range_name(i));
    const double radius =
        2.84 * (atmosphere.long_term_radius(w0, lambda, ranges[i]) +
                3.0 * std::sqrt(atmosphere.beam_wander_variance(w0, lambda, ranges[i])));
    // Tails to 1e-4 of G: far below the spread between realisations, at a quarter of the grid of 1e-6.
    grids[i] = detail::spectrum_grid(system, receivers[i], ranges[i], range_spacing[i], radius, n,
                                     o.max_spectrum_grid, i, 1e-4);
  }
  double np_max = 0.0;
  for (std::size_t g : grids) np_max = std::max(np_max, static_cast<double>(g));
  const double n2 = double(n) * double(n);
  checks::memory("beam_grid", static_cast<double>(n),
                 8.0 * n2 * double(ranges.size()) + 16.0 * n2 * double(o.screens + 1) +
                     double(threads) * (16.0 * 5.0 * n2 + CouplingMap::workspace(
                                                              n, static_cast<std::size_t>(np_max))),
                 "lower beam_grid, screens or the number of ranges");
  detail::parallel_for(ranges.size(), threads, [&](std::size_t i) {
    maps[i] = std::make_unique<CouplingMap>(system, receivers[i], ranges[i], range_spacing[i], n,
                                            grids[i]);
  });
  return maps;
}

// The transmit-only path (TurbulencePaths::transmit). The transmitter's segment is the same in every
// realisation: run once, its ranges' G copied to every row and the field at the first screen kept for every
// realisation's departure from it.
TurbulentOverlap transmit_path(const LidarSystem& system, const std::vector<double>& ranges,
                               const TurbulenceOptions& o, int threads, const TurbulentPlan& plan,
                               const std::vector<std::unique_ptr<PhaseScreenGenerator>>& generators,
                               const std::vector<std::unique_ptr<CouplingMap>>& maps, double dx0) {
  const std::size_t n = o.beam_grid;
  Field start = Field::gaussian(system.beam.wavelength, system.beam.waist_radius, n, dx0);
  std::vector<double> before_screens(ranges.size(), 0.0);
  std::vector<char> shared(ranges.size(), 0);
  {
    Field work = start;
    std::vector<double> column_sums(2 * n);
    plan.segments.front().departure.execute(start, nullptr, nullptr, nullptr);
    arrive(plan.segments.front(), plan, maps, start, work, column_sums,
           [&](std::size_t range, double g) { before_screens[range] = g, shared[range] = 1; });
  }
  TurbulentOverlap out = zero_rows(o.realizations, ranges.size(), false);
  for (std::vector<double>& g : out.overlap)
    for (std::size_t i = 0; i < ranges.size(); ++i)
      if (shared[i]) g[i] = before_screens[i];
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
    std::vector<Field> fields(count, start);
    Field work = start;
    std::array<std::vector<double>, 2> screen_pair;  // the pair's screens at one plane
    ComplexBuffer spectrum;                          // their transform's workspace
    std::vector<double> column_sums(2 * n);
    for (std::size_t s = 1; s < plan.segments.size(); ++s) {
      const Segment& segment = plan.segments[s];
      generators[segment.screen]->generate_pair(screen_stream(o.seed, segment.screen), k0 / 2,
                                                screen_pair, spectrum);
      for (std::size_t c = 0; c < count; ++c) {
        segment.departure.execute(fields[c], s == 1 ? start.values.data() : nullptr,
                                  screen_pair[(k0 + c) % 2].data(), nullptr);
        arrive(segment, plan, maps, fields[c], work, column_sums,
               [&](std::size_t range, double g) { out.overlap[k0 - first + c][range] = g; });
      }
    }
    for (std::size_t c = 0; c < count; ++c) {
      const Field& last = plan.segments.size() > 1 ? fields[c] : start;
      const Vec2 centre = last.centroid();
      out.wander_x[k0 - first + c] = centre.x;
      out.wander_y[k0 - first + c] = centre.y;
      out.radius_last[k0 - first + c] = last.beam_radius();
    }
  });
  for (std::vector<double>& g : out.overlap)
    checks::overlap_values(g, ranges, detail::kFoOverlapSlack, "overlap_fo_turbulent");
  return out;
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
      both ? both_paths(system, ranges, o, threads, plan, generators, dx0)
           : transmit_path(system, ranges, o, threads, plan, generators,
                           coupling_maps(system, ranges, atmosphere, o, threads, range_spacing),
                           dx0);
  for (std::size_t j = 0; j < placements.size(); ++j) {
    out.screen_range.push_back(placements[j].range);
    out.screen_spacing.push_back(generators[j]->spacing());
    out.screen_r0.push_back(placements[j].r0);
  }
  return out;
}

}  // namespace lidar_overlap
