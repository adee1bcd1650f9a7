#include "atmosphere/segment_plan.hpp"

#include <algorithm>
#include <utility>

#include "core/checks.hpp"

namespace lidar_overlap::detail {

TurbulentPlan plan_propagation(const std::vector<double>& screen_ranges,
                               const std::vector<double>& ranges,
                               const std::vector<double>& windows, double pupil_window,
                               std::size_t n, double lambda) {
  TurbulentPlan plan;
  std::vector<Plane>& planes = plan.planes;
  for (std::size_t j = 0; j < screen_ranges.size(); ++j)
    planes.push_back({screen_ranges[j], static_cast<int>(j), -1});
  for (std::size_t i = 0; i < ranges.size(); ++i)
    planes.push_back({ranges[i], -1, static_cast<int>(i)});
  std::stable_sort(planes.begin(), planes.end(),
                   [](const Plane& a, const Plane& b) { return a.z < b.z; });
  if (windows.size() != planes.size())
    checks::fail("windows", static_cast<double>(windows.size()),
                 "one side per plane (internal error)");
  plan.spacing.assign(planes.size(), 0.0);
  double z_a = 0.0, d_a = pupil_window / static_cast<double>(n), incoming = 0.0;
  int screen = -1;
  for (std::size_t p = 0; p < planes.size();) {
    // The segment ends at the next screen's plane (or the last plane); ranges at that screen's range are
    // read from the same spectrum.
    std::size_t e = p;
    while (e + 1 < planes.size() && planes[e].screen < 0) ++e;
    std::size_t f = e;
    if (planes[e].screen >= 0)
      while (f + 1 < planes.size() && planes[f + 1].z == planes[e].z && planes[f + 1].screen < 0)
        ++f;
    const double span = planes[e].z - z_a, d_b = windows[e] / static_cast<double>(n);
    // The cone through both ends: spacing d_a (1 + c dz).
    const double c = span > 0.0 ? (d_b / d_a - 1.0) / span : 0.0;
    Segment s{screen, Departure(n, d_a, incoming, c, lambda), {}, {}};
    for (std::size_t q = p; q <= f; ++q)
      if (q != e) s.targets.push_back(q);
    s.targets.push_back(e);
    for (std::size_t q : s.targets) {
      s.arrivals.emplace_back(n, d_a, planes[q].z - z_a, c, lambda);
      plan.spacing[q] = s.arrivals.back().spacing();
    }
    incoming = s.arrivals.back().q3_curvature();
    d_a = s.arrivals.back().spacing();
    z_a = planes[e].z;
    screen = planes[e].screen;
    plan.segments.push_back(std::move(s));
    p = f + 1;
  }
  return plan;
}

}  // namespace lidar_overlap::detail
