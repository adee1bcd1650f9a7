#include "lidar_overlap/geometry/overlap_rt.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>

#include "core/cancel_every.hpp"
#include "core/checks.hpp"
#include "core/constants.hpp"
#include "core/entry_checks.hpp"
#include "core/parallel.hpp"
#include "geometry/beam_integral.hpp"
#include "geometry/receiver_coupling.hpp"
#include "geometry/rt_entry.hpp"

namespace lidar_overlap {

namespace detail {

void check_rt_options(const RtOptions& options) {
  checks::tolerance("tolerance", options.tolerance);
  if (options.max_segments < 1) checks::fail("max_segments", 0, "a count >= 1");
}

RtEntry overlap_rt_entry(const LidarSystem& system, const Receiver& rx, const RtOptions& opt) {
  return sum_over_terms(
      system, rx, opt.tolerance, [&](const CouplingTerm& term, Vec2 center, double w, double tol) {
        const beam_integral::Kinks kinks(term);
        const std::optional<Vec2> s = term.symmetry_center();
        return s ? beam_integral::radial_integral(term, kinks, *s, norm(center - *s), w, {1.0, 0.0},
                                                  tol, opt.max_segments)
                 : beam_integral::planar_mean(term, kinks, center, w,
                                              beam_integral::mirror_symmetric(term, center), tol,
                                              opt.max_segments);
      });
}

RtOverlap collect_rt_entries(const std::vector<RtEntry>& entries, const std::vector<double>& ranges,
                             double tolerance, const std::string& method) {
  const std::size_t n = entries.size();
  RtOverlap out;
  out.overlap.resize(n);
  out.error_estimate.resize(n);
  out.converged.resize(n);
  std::vector<double> slack(n);
  for (std::size_t i = 0; i < n; ++i) {
    out.overlap[i] = entries[i].value;
    out.error_estimate[i] = entries[i].error;
    out.converged[i] = entries[i].converged;
    out.evaluations += entries[i].evaluations;
    slack[i] = std::max(tolerance, entries[i].error);  // as overlap_rt on this entry alone
  }
  checks::overlap_values(out.overlap, ranges, slack, method);
  return out;
}

RtOverlap rt_over_ranges(const LidarSystem& system, const std::vector<double>& ranges,
                         const RtOptions& options,
                         const std::function<RtEntry(const Receiver&)>& at,
                         const std::string& name) {
  system.validate();
  check_rt_options(options);
  const int threads = checked_threads_and_ranges(system, ranges, options.threads);

  // Receivers are built before the parallel region: nothing throws inside it.
  std::vector<Receiver> receivers;
  receivers.reserve(ranges.size());
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    cancellation_point_every(i);  // millions of ranges take seconds to prepare on a busy core
    receivers.emplace_back(system, ranges[i]);
  }

  const std::size_t n = ranges.size();
  RtOverlap out;
  out.overlap.assign(n, 0.0);
  out.error_estimate.assign(n, 0.0);
  out.converged.assign(n, true);
  out.axisymmetric = system.is_axisymmetric();
  std::vector<RtEntry> results(n);
  parallel_for(n, threads, [&](std::size_t i) { results[i] = at(receivers[i]); });
  for (std::size_t i = 0; i < n; ++i) {
    out.overlap[i] = results[i].value;
    out.error_estimate[i] = results[i].error;
    out.converged[i] = results[i].converged;
    out.evaluations += results[i].evaluations;
  }
  double slack = options.tolerance;
  for (double e : out.error_estimate) slack = std::max(slack, e);
  checks::overlap_values(out.overlap, ranges, slack, name);
  return out;
}

}  // namespace detail

RtOverlap overlap_rt(const LidarSystem& system, const std::vector<double>& ranges,
                     const RtOptions& options) {
  return detail::rt_over_ranges(
      system, ranges, options,
      [&](const Receiver& rx) { return detail::overlap_rt_entry(system, rx, options); },
      "overlap_rt");
}

RtOverlap overlap_rt_batch(const std::vector<LidarSystem>& systems,
                           const std::vector<double>& ranges, const RtOptions& options) {
  const std::size_t n = systems.size();
  if (ranges.size() != n)
    checks::fail(
        "ranges", static_cast<double>(ranges.size()),
        "one range per system: expected " + std::to_string(n) + " ranges (the size of systems)");
  if (n > kMaxBatchEntries)
    checks::fail("systems", static_cast<double>(n),
                 "at most " + std::to_string(kMaxBatchEntries) + " entries");
  detail::check_rt_options(options);
  const int threads = detail::checked_threads_and_ranges(systems, ranges, options.threads);
  checks::memory("systems", static_cast<double>(n),
                 static_cast<double>(n) * (sizeof(detail::RtEntry) + 3 * sizeof(double) + 1),
                 "split the batch");

  // Each receiver is built inside the region (its system and range are valid, so it does not throw; were it
  // to, parallel_for carries the exception out): a batch keeps no table of receivers.
  std::vector<detail::RtEntry> results(n);
  detail::parallel_for(n, threads, [&](std::size_t i) {
    results[i] = detail::overlap_rt_entry(systems[i], Receiver(systems[i], ranges[i]), options);
  });
  RtOverlap out =
      detail::collect_rt_entries(results, ranges, options.tolerance, "overlap_rt_batch");
  out.axisymmetric = std::all_of(systems.begin(), systems.end(),
                                 [](const LidarSystem& s) { return s.is_axisymmetric(); });
  return out;
}

double emitter_coupling_rt(const LidarSystem& system, double z, Vec2 position) {
  checks::coordinate("position", position);
  std::vector<double> g{Receiver(system, z).coupling(position)};
  checks::overlap_values(g, {z}, 1e-9, "emitter_coupling_rt");  // exact geometry: round-off only
  return g[0];
}

}  // namespace lidar_overlap
