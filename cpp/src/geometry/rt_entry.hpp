// One entry of the ray-tracing overlap (G of one system at one range), shared by overlap_rt, its batch
// form, alignment_map and the masked overlap so that all of them give the same bits. Internal header, not
// installed.
#pragma once

#include <cmath>
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "geometry/beam_integral.hpp"
#include "geometry/receiver_coupling.hpp"
#include "lidar_overlap/geometry/overlap_rt.hpp"

namespace lidar_overlap::detail {

// One beam integral's value, error bound, evaluations and convergence.
using RtEntry = beam_integral::RangeResult;

// G of `system` at the receiver's range through m apertures at once (the full one, or the masks of a telecover
// test): the coupling split into the receiver's terms (at most two), each integrated over the beam by
// `integrate(term, beam_center, w, tolerance)` (m entries, one per aperture) with its share of `tolerance`, and
// summed. An obstruction's term cancels the unobstructed one where its shadow covers all the light that passes;
// integrated on different breakpoints they then differ by round-off of either sign, which means G = 0.
template <class IntegrateMany>
std::vector<RtEntry> sum_over_terms_many(const LidarSystem& system, const Receiver& rx,
                                         double tolerance, std::size_t m, IntegrateMany integrate) {
  const double z = rx.range();
  const double w = system.beam.radius(z);
  const Vec2 center = system.beam.center(z);
  CouplingTerm terms[2];
  // 10 sigma = 5 w: the beam power beyond is below exp(-50).
  const std::size_t n_terms = rx.terms(center, 5.0 * w, terms);
  const double share = tolerance / static_cast<double>(n_terms);
  std::vector<RtEntry> total(m);
  std::vector<double> magnitude(m, 0.0);
  for (std::size_t t = 0; t < n_terms; ++t) {
    const std::vector<RtEntry> r = integrate(terms[t], center, w, share);
    for (std::size_t k = 0; k < m; ++k) {
      total[k].add(r[k]);
      magnitude[k] += std::abs(r[k].value);
    }
  }
  for (std::size_t k = 0; k < m; ++k)
    if (std::abs(total[k].value) <= 16.0 * std::numeric_limits<double>::epsilon() * magnitude[k])
      total[k].value = 0.0;
  return total;
}

// The same through one aperture: `integrate` returns one RtEntry.
template <class Integrate>
RtEntry sum_over_terms(const LidarSystem& system, const Receiver& rx, double tolerance,
                       Integrate integrate) {
  return sum_over_terms_many(system, rx, tolerance, 1,
                             [&](const CouplingTerm& term, Vec2 center, double w, double tol) {
                               return std::vector<RtEntry>{integrate(term, center, w, tol)};
                             })[0];
}

// Checks the options every RT entry point shares (tolerance, max_segments); throws std::invalid_argument.
void check_rt_options(const RtOptions& options);

// G of `system` at the receiver's range. Does not throw for a valid system, range and options.
RtEntry overlap_rt_entry(const LidarSystem& system, const Receiver& receiver,
                         const RtOptions& options);

// Entries as an RtOverlap (axisymmetric left false), each checked like a single call: finite, in [0, 1] up
// to max(tolerance, its own error) (checks::overlap_values, naming `method` and ranges[i]).
RtOverlap collect_rt_entries(const std::vector<RtEntry>& entries, const std::vector<double>& ranges,
                             double tolerance, const std::string& method);

// The range loop of the RT entry points over one system (full aperture, masked): the entry checks, the
// receivers built before the parallel region (nothing throws inside it), `at(receiver)` at every range in
// parallel, and the result's assembly and value checks; `name` is the engine's name in value errors.
RtOverlap rt_over_ranges(const LidarSystem& system, const std::vector<double>& ranges,
                         const RtOptions& options,
                         const std::function<RtEntry(const Receiver&)>& at,
                         const std::string& name);

}  // namespace lidar_overlap::detail
