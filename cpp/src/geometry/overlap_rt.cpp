#include "lidar_overlap/geometry/overlap_rt.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "core/checks.hpp"
#include "core/constants.hpp"
#include "core/entry_checks.hpp"
#include "core/parallel.hpp"
#include "core/quadrature.hpp"
#include "core/special_functions.hpp"
#include "geometry/rt_entry.hpp"

namespace lidar_overlap {

namespace {

constexpr std::size_t kMaxKinks = 16;  // 4 moving discs: 12 tangency circles; 2 gates

using RangeResult = detail::RtEntry;

// Circles in the scatterer plane across which a term has a kink (CouplingTerm::kink_circles).
struct Kinks {
  Disc circles[kMaxKinks];
  std::size_t n = 0;
  explicit Kinks(const CouplingTerm& t) : n(t.kink_circles(circles, kMaxKinks)) {}
};

// Distances t > 0 at which the ray center + t dir (|dir| = 1) crosses a kink circle.
std::size_t crossings(const Kinks& k, Vec2 center, Vec2 dir, double* out) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < k.n; ++i) {
    const Vec2 q = center - k.circles[i].center;
    const double half_b = dot(q, dir), c = dot(q, q) - k.circles[i].radius * k.circles[i].radius;
    const double disc = half_b * half_b - c;
    if (disc < 0.0) continue;
    const double h = -(half_b + std::copysign(std::sqrt(disc), half_b));  // stable roots h and c/h
    for (double t : {h, h != 0.0 ? c / h : 0.0})
      if (t > 0.0 && std::isfinite(t)) out[n++] = t;
  }
  return n;
}

// Sorted breakpoints: lo, the crossings inside (lo, hi), hi.
std::size_t breakpoints(const Kinks& k, Vec2 center, Vec2 dir, double lo, double hi, double* points) {
  double radii[2 * kMaxKinks];
  const std::size_t nk = crossings(k, center, dir, radii);
  std::size_t n = 0;
  points[n++] = lo;
  for (std::size_t i = 0; i < nk; ++i) {
    if (radii[i] > lo && radii[i] < hi) points[n++] = radii[i];
  }
  points[n++] = hi;
  std::sort(points, points + n);
  return n;
}

// int term(origin + rho dir) p(rho) d rho, with p the density of the distance from `origin` of a
// point of the Gaussian beam (1/e^2 radius w, so sigma = w/2) centred `nu` away: the Rice density,
// Rayleigh for nu = 0. For a term symmetric about `origin` this is its beam-weighted mean whatever
// the beam offset; with nu = 0 and the origin at the beam centre it is the mean along `dir`.
RangeResult radial_integral(const CouplingTerm& term, const Kinks& kinks, Vec2 origin, double nu, double w,
                            Vec2 dir, double tolerance, std::size_t max_segments) {
  const double var = 0.25 * w * w;
  // Beyond 10 sigma = 5 w from nu the density is below exp(-50) of its peak.
  const double lo = std::max(0.0, nu - 5.0 * w), hi = nu + 5.0 * w;
  double points[2 * kMaxKinks + 2];
  const std::size_t n = breakpoints(kinks, origin, dir, lo, hi, points);
  auto integrand = [&](double rho) {
    const double d = rho - nu;
    const double density = rho / var * std::exp(-0.5 * d * d / var) * scaled_bessel_i0(rho * nu / var);
    return density == 0.0 ? 0.0 : density * term(origin + rho * dir);
  };
  const QuadratureResult q = integrate(integrand, points, n, tolerance, max_segments);
  return {q.value, q.error, q.evaluations, q.converged};
}

// A term with no centre of symmetry: the mean over directions of the radial mean. When the term is
// mirror-symmetric about the line through the beam centre and the origin (all disc shifts along it),
// half the directions suffice.
RangeResult planar_mean(const CouplingTerm& term, const Kinks& kinks, Vec2 center, double w,
                        double tolerance, std::size_t max_segments) {
  bool mirror = true;
  for (std::size_t i = 0; i < term.n_discs; ++i) {
    const Vec2 b = term.discs[i].shift;
    mirror = mirror && (b.x * center.y - b.y * center.x) == 0.0;
  }
  for (std::size_t g = 0; g < term.n_gates; ++g) {
    const Vec2 b = term.gates[g].shift;
    mirror = mirror && (b.x * center.y - b.y * center.x) == 0.0;
  }
  const double phi0 = (center.x != 0.0 || center.y != 0.0) ? std::atan2(center.y, center.x) : 0.0;
  const double span = mirror ? kPi : 2.0 * kPi;

  // The radial mean is not smooth in direction where a ray from the beam centre grazes a kink
  // circle: those tangent directions become breakpoints of the angular integral.
  double breaks[2 * kMaxKinks + 3];
  std::size_t nb = 0;
  for (double f : {0.0, 0.5, 1.0}) breaks[nb++] = f * span;
  for (std::size_t i = 0; i < kinks.n; ++i) {
    const Vec2 q = kinks.circles[i].center - center;
    const double d = norm(q), rho = kinks.circles[i].radius;
    if (!(d > rho)) continue;
    const double mid = std::atan2(q.y, q.x) - phi0, half = std::asin(rho / d);
    for (double phi : {mid - half, mid + half}) {
      phi = std::remainder(phi, 2.0 * kPi);  // (-pi, pi]
      if (mirror) phi = std::abs(phi);      // the lower half mirrors the upper one
      else if (phi < 0.0) phi += 2.0 * kPi;
      if (phi > 0.0 && phi < span) breaks[nb++] = phi;
    }
  }
  std::sort(breaks, breaks + nb);

  RangeResult inner;
  double inner_error = 0.0;
  auto mean_over_direction = [&](double phi) {
    const double a = phi0 + phi;
    const RangeResult r = radial_integral(term, kinks, center, 0.0, w, {std::cos(a), std::sin(a)},
                                          0.25 * tolerance, max_segments);
    inner.evaluations += r.evaluations;
    inner.converged = inner.converged && r.converged;
    inner_error = std::max(inner_error, r.error);
    return r.value / span;
  };
  const QuadratureResult q = integrate(mean_over_direction, breaks, nb, 0.75 * tolerance, max_segments);
  return {q.value, q.error + inner_error, inner.evaluations, inner.converged && q.converged};
}

}  // namespace

namespace detail {

void check_rt_options(const RtOptions& options) {
  checks::in_open_unit("tolerance", options.tolerance);
  if (options.max_segments < 1) checks::fail("max_segments", 0, "a count >= 1");
}

RtEntry overlap_rt_entry(const LidarSystem& system, const Receiver& rx, const RtOptions& opt) {
  const double z = rx.range();
  const double w = system.beam.radius(z);
  const Vec2 center = system.beam.center(z);
  CouplingTerm terms[2];
  // 10 sigma = 5 w: the beam power beyond is below exp(-50).
  const std::size_t n_terms = rx.terms(center, 5.0 * w, terms);
  const double tolerance = opt.tolerance / static_cast<double>(n_terms);
  RangeResult total;
  double magnitude = 0.0;
  for (std::size_t t = 0; t < n_terms; ++t) {
    const Kinks kinks(terms[t]);
    const std::optional<Vec2> s = terms[t].symmetry_center();
    const RangeResult r = s ? radial_integral(terms[t], kinks, *s, norm(center - *s), w, {1.0, 0.0}, tolerance,
                                              opt.max_segments)
                            : planar_mean(terms[t], kinks, center, w, tolerance, opt.max_segments);
    total.add(r);
    magnitude += std::abs(r.value);
  }
  // An obstruction's term cancels the unobstructed one where its shadow covers all the light that passes;
  // integrated on different breakpoints, they then differ by round-off of either sign, which means G = 0.
  if (std::abs(total.value) <= 16.0 * std::numeric_limits<double>::epsilon() * magnitude) total.value = 0.0;
  return total;
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

}  // namespace detail

RtOverlap overlap_rt(const LidarSystem& system, const std::vector<double>& ranges,
                     const RtOptions& options) {
  system.validate();
  detail::check_rt_options(options);
  const int threads = detail::checked_threads_and_ranges(system, ranges, options.threads);

  // Receivers are built before the parallel region: nothing throws inside it.
  std::vector<Receiver> receivers;
  receivers.reserve(ranges.size());
  for (double z : ranges) receivers.emplace_back(system, z);

  const std::size_t n = ranges.size();
  RtOverlap out;
  out.overlap.assign(n, 0.0);
  out.error_estimate.assign(n, 0.0);
  out.converged.assign(n, true);
  out.axisymmetric = system.is_axisymmetric();
  std::vector<RangeResult> results(n);
  detail::parallel_for(n, threads,
                       [&](std::size_t i) { results[i] = detail::overlap_rt_entry(system, receivers[i], options); });
  for (std::size_t i = 0; i < n; ++i) {
    out.overlap[i] = results[i].value;
    out.error_estimate[i] = results[i].error;
    out.converged[i] = results[i].converged;
    out.evaluations += results[i].evaluations;
  }
  double slack = options.tolerance;
  for (double e : out.error_estimate) slack = std::max(slack, e);
  checks::overlap_values(out.overlap, ranges, slack, "overlap_rt");
  return out;
}

RtOverlap overlap_rt_batch(const std::vector<LidarSystem>& systems, const std::vector<double>& ranges,
                           const RtOptions& options) {
  const std::size_t n = systems.size();
  if (ranges.size() != n)
    checks::fail("ranges", static_cast<double>(ranges.size()),
                 "one range per system: expected " + std::to_string(n) + " ranges (the size of systems)");
  if (n > kMaxBatchEntries)
    checks::fail("systems", static_cast<double>(n), "at most " + std::to_string(kMaxBatchEntries) + " entries");
  detail::check_rt_options(options);
  const int threads = detail::checked_threads_and_ranges(systems, ranges, options.threads);
  checks::memory("systems", static_cast<double>(n),
                 static_cast<double>(n) * (sizeof(RangeResult) + 3 * sizeof(double) + 1),
                 "split the batch");

  // Each receiver is built inside the region (its system and range are valid, so it does not throw; were it
  // to, parallel_for carries the exception out): a batch keeps no table of receivers.
  std::vector<RangeResult> results(n);
  detail::parallel_for(n, threads, [&](std::size_t i) {
    results[i] = detail::overlap_rt_entry(systems[i], Receiver(systems[i], ranges[i]), options);
  });
  RtOverlap out = detail::collect_rt_entries(results, ranges, options.tolerance, "overlap_rt_batch");
  out.axisymmetric =
      std::all_of(systems.begin(), systems.end(), [](const LidarSystem& s) { return s.is_axisymmetric(); });
  return out;
}

double emitter_coupling_rt(const LidarSystem& system, double z, Vec2 position) {
  checks::coordinate("position", position);
  std::vector<double> g{Receiver(system, z).coupling(position)};
  checks::overlap_values(g, {z}, 1e-9, "emitter_coupling_rt");  // exact geometry: round-off only
  return g[0];
}

}  // namespace lidar_overlap
