#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "atmosphere/turbulent_paths.hpp"
#include "core/checks.hpp"
#include "core/entry_checks.hpp"
#include "core/parallel.hpp"
#include "fourier/fo_receiver.hpp"
#include "fourier/overlap_fo_detail.hpp"

namespace lidar_overlap::detail {

namespace {

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

}  // namespace

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

}  // namespace lidar_overlap::detail
