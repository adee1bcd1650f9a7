#include "lidar_overlap/geometry/alignment_map.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <stdexcept>

#include "core/cancel_every.hpp"
#include "core/checks.hpp"
#include "core/entry_checks.hpp"
#include "core/parallel.hpp"
#include "geometry/receiver_coupling.hpp"
#include "geometry/rt_entry.hpp"

namespace lidar_overlap {

namespace {

constexpr AlignmentParameter kParameters[] = {AlignmentParameter::tilt_x,
                                              AlignmentParameter::tilt_y,
                                              AlignmentParameter::beam_offset_x,
                                              AlignmentParameter::beam_offset_y,
                                              AlignmentParameter::detector_offset_x,
                                              AlignmentParameter::detector_offset_y,
                                              AlignmentParameter::defocus};

std::string valid_names() {
  std::string s;
  for (AlignmentParameter p : kParameters)
    s += (s.empty() ? "" : ", ") + std::string(alignment_parameter_name(p));
  return s;
}

// Values finite and strictly increasing, each making a valid system when added alone. The system checks
// are per scalar (each tilt and offset component, the defocus against the focal length, which no axis
// varies), so the axes' values valid one by one make every grid point valid.
void check_axis(const LidarSystem& system, const AlignmentAxis& axis) {
  const std::string name = alignment_parameter_name(axis.parameter);
  if (axis.values.empty()) checks::fail(name, 0, "a non-empty list of values");
  for (std::size_t i = 0; i < axis.values.size(); ++i) {
    const std::string item = name + "[" + std::to_string(i) + "]";
    checks::finite(item, axis.values[i]);
    if (i > 0 && !(axis.values[i] > axis.values[i - 1]))
      checks::fail(item, axis.values[i],
                   "values strictly increasing: above " + checks::number(axis.values[i - 1]));
    try {
      misaligned(system, axis.parameter, axis.values[i]).validate();
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(item + " = " + checks::number(axis.values[i]) +
                                  " makes an invalid system: " + e.what());
    }
  }
}

bool moves_beam_only(AlignmentParameter p) {
  return p == AlignmentParameter::tilt_x || p == AlignmentParameter::tilt_y ||
         p == AlignmentParameter::beam_offset_x || p == AlignmentParameter::beam_offset_y;
}

// For each entry (grid point e / n_ranges at range e % n_ranges), the first entry whose G is the same
// computation, bit for bit: itself unless the axes only move the beam. The receiver (telescope, detector, range)
// and the beam radius are then the same at every grid point of a range, and each coupling term's integral
// depends on the beam centre c only through |c - S| when the term has a centre of symmetry S, through c
// otherwise; the terms themselves depend on c only through whether the shadow disc is dropped. Grid points at
// the same distance from S (the mirror images of a symmetric grid: a 41 x 41 tilt map of a coaxial lidar has
// 231 distinct distances) are traced once.
template <class PointSystem>
std::vector<std::size_t> equivalent_entries(const LidarSystem& system,
                                            const std::vector<AlignmentAxis>& axes,
                                            const std::vector<double>& ranges,
                                            const PointSystem& point_system, int threads) {
  const std::size_t n_ranges = ranges.size(), points = [&] {
    std::size_t p = 1;
    for (const AlignmentAxis& a : axes) p *= a.values.size();
    return p;
  }();
  std::vector<std::size_t> source(points * n_ranges);
  for (std::size_t e = 0; e < source.size(); ++e) source[e] = e;
  for (const AlignmentAxis& a : axes)
    if (!moves_beam_only(a.parameter)) return source;
  // Per term: its disc count and (|c - S|, inf) or (c.x, c.y), compared bit for bit (-0 is not 0 to atan2).
  using Key = std::array<std::uint64_t, 6>;
  auto bits = [](double x) {
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    return b;
  };
  std::vector<Receiver>
      receivers;  // built before the parallel region (the beam does not enter them)
  for (std::size_t z = 0; z < ranges.size(); ++z) {
    detail::cancellation_point_every(z);
    receivers.emplace_back(system, ranges[z]);
  }
  detail::parallel_for(n_ranges, threads, [&](std::size_t z) {
    const Receiver& rx = receivers[z];
    const double w = system.beam.radius(ranges[z]);
    std::vector<Key> keys(points);
    std::vector<std::size_t> order(points);
    for (std::size_t p = 0; p < points; ++p) {
      detail::cancellation_point_every(p);  // one range of a 10^6-point map is a long iteration
      const Vec2 c = point_system(p).beam.center(ranges[z]);
      CouplingTerm terms[2];
      const std::size_t n_terms = rx.terms(c, 5.0 * w, terms);  // as sum_over_terms
      Key k{};
      for (std::size_t t = 0; t < n_terms; ++t) {
        const std::optional<Vec2> center = terms[t].symmetry_center();
        k[3 * t] = terms[t].n_discs;
        k[3 * t + 1] = bits(center ? norm(c - *center) : c.x);
        k[3 * t + 2] = bits(center ? HUGE_VAL : c.y);
      }
      keys[p] = k;
      order[p] = p;
    }
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });
    for (std::size_t i = 1; i < points; ++i)
      if (keys[order[i]] == keys[order[i - 1]])
        source[order[i] * n_ranges + z] = source[order[i - 1] * n_ranges + z];
  });
  return source;
}

}  // namespace

const char* alignment_parameter_name(AlignmentParameter p) {
  switch (p) {
    case AlignmentParameter::tilt_x:
      return "tilt_x";
    case AlignmentParameter::tilt_y:
      return "tilt_y";
    case AlignmentParameter::beam_offset_x:
      return "beam_offset_x";
    case AlignmentParameter::beam_offset_y:
      return "beam_offset_y";
    case AlignmentParameter::detector_offset_x:
      return "detector_offset_x";
    case AlignmentParameter::detector_offset_y:
      return "detector_offset_y";
    case AlignmentParameter::defocus:
      return "defocus";
  }
  return "?";
}

AlignmentParameter alignment_parameter_from_name(const std::string& name,
                                                 const std::string& parameter) {
  for (AlignmentParameter p : kParameters)
    if (name == alignment_parameter_name(p)) return p;
  throw std::invalid_argument(parameter + ": '" + name +
                              "' is not an alignment parameter: expected one of " + valid_names());
}

LidarSystem misaligned(const LidarSystem& system, AlignmentParameter p, double delta) {
  LidarSystem s = system;
  switch (p) {
    case AlignmentParameter::tilt_x:
      s.beam.tilt.x += delta;
      break;
    case AlignmentParameter::tilt_y:
      s.beam.tilt.y += delta;
      break;
    case AlignmentParameter::beam_offset_x:
      s.beam.offset.x += delta;
      break;
    case AlignmentParameter::beam_offset_y:
      s.beam.offset.y += delta;
      break;
    case AlignmentParameter::detector_offset_x:
      s.detector.offset.x += delta;
      break;
    case AlignmentParameter::detector_offset_y:
      s.detector.offset.y += delta;
      break;
    case AlignmentParameter::defocus:
      s.detector.defocus += delta;
      break;
  }
  return s;
}

AlignmentMap alignment_map(const LidarSystem& system, const std::vector<AlignmentAxis>& axes,
                           const std::vector<double>& ranges, const RtOptions& options) {
  system.validate();
  detail::check_rt_options(options);
  if (axes.empty() || axes.size() > 2)
    checks::fail("axes", static_cast<double>(axes.size()), "one or two axes");
  if (axes.size() == 2 && axes[0].parameter == axes[1].parameter)
    checks::fail("axes", 2,
                 std::string("two different parameters: ") +
                     alignment_parameter_name(axes[0].parameter) + " is given twice");
  double points = 1.0;  // in double: sizes from the caller may multiply past size_t
  for (const AlignmentAxis& a : axes) points *= static_cast<double>(a.values.size());
  if (!(points <= static_cast<double>(kMaxAlignmentPoints)))
    checks::fail("axes", points,
                 "at most " + std::to_string(kMaxAlignmentPoints) +
                     " grid points (the product of "
                     "the axis sizes)");
  const double entries = points * static_cast<double>(ranges.size());
  if (!(entries <= static_cast<double>(kMaxAlignmentEntries)))
    checks::fail(
        "ranges", static_cast<double>(ranges.size()),
        "at most " + std::to_string(kMaxAlignmentEntries) + " grid points x ranges in one map");
  for (const AlignmentAxis& a : axes) check_axis(system, a);
  const int threads = detail::checked_threads_and_ranges(system, ranges, options.threads);
  checks::memory("axes", points, entries * (sizeof(detail::RtEntry) + 4 * sizeof(double) + 1),
                 "use fewer grid points or ranges");

  const std::size_t n_ranges = ranges.size(), n1 = axes.size() == 2 ? axes[1].values.size() : 1;
  const std::size_t n = static_cast<std::size_t>(entries);
  // Entry e is grid point e / n_ranges (row-major over the axes) at range e % n_ranges. The grid point's
  // system and receiver are built inside the region: both are valid (checked above), so nothing throws
  // there, and parallel_for would carry an exception out if it did.
  auto point_system = [&](std::size_t point) {
    LidarSystem s = misaligned(system, axes[0].parameter, axes[0].values[point / n1]);
    return axes.size() == 2 ? misaligned(s, axes[1].parameter, axes[1].values[point % n1]) : s;
  };
  std::vector<detail::RtEntry> results(n);
  const std::vector<std::size_t> source =
      equivalent_entries(system, axes, ranges, point_system, threads);
  detail::parallel_for(n, threads, [&](std::size_t e) {
    if (source[e] != e) return;
    const LidarSystem s = point_system(e / n_ranges);
    results[e] = detail::overlap_rt_entry(s, Receiver(s, ranges[e % n_ranges]), options);
  });
  for (std::size_t e = 0; e < n; ++e) results[e] = results[source[e]];
  std::vector<double> entry_ranges(n);
  for (std::size_t e = 0; e < n; ++e) entry_ranges[e] = ranges[e % n_ranges];

  AlignmentMap out;
  for (const AlignmentAxis& a : axes) out.shape.push_back(a.values.size());
  out.shape.push_back(n_ranges);
  out.values =
      detail::collect_rt_entries(results, entry_ranges, options.tolerance, "alignment_map");
  out.values.axisymmetric = true;
  for (std::size_t p = 0; p < n / n_ranges; ++p) {
    detail::cancellation_point_every(p);
    out.values.axisymmetric = out.values.axisymmetric && point_system(p).is_axisymmetric();
  }
  return out;
}

}  // namespace lidar_overlap
