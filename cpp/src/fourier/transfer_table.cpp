#include "fourier/transfer_table.hpp"

#include <algorithm>
#include <cmath>

#include "core/constants.hpp"
#include "fourier/otf.hpp"

namespace lidar_overlap::detail {

namespace {

// Chebyshev panels: kPanelNodes points (second kind, ends included) over kPanelPeriods periods of T's
// fastest oscillation interpolate it to ~1e-13 of its scale (the coefficients fall like J_n(pi x
// periods) beyond n ~ 2 pi periods), where the uniform table asks for 24 points per period.
constexpr std::size_t kPanelNodes = 80;
constexpr double kPanelPeriods = 16.0;

}  // namespace

TransferTable::TransferTable(const LidarSystem& system, const FoReceiver& rx, double q_max) {
  const double r_d = system.detector.radius;
  const double period = 1.0 / std::max({r_d, rx.blur_radius(), 1.0 / rx.cutoff()});
  nt_ = std::min<std::size_t>(1 << 16, 6 + checks::saturate(24.0 * q_max / period));
  const double h = q_max / (nt_ - 3);
  inv_h_ = 1.0 / h;
  table_.assign(nt_ + 3, 0.0);
  auto exact = [&](double q) { return rx.otf(q) * disc_transform(r_d, q); };
  // Node t holds q = (t - 2) h; nodes 0 and 1 mirror 4 and 3 (the even extension).
  const std::size_t last = nt_ + 2;
  // T is analytic between the OTF's kinks (one shifted pupil edge crossing another: shifts 2 R and, with an
  // obstruction r, R -+ r and 2 r) but only algebraic next to them: panels end there, and a panel that
  // touches a kink other than q = 0 is evaluated point by point.
  const AnnularPupil& p = rx.pupil();
  const double to_q = 1.0 / (system.beam.wavelength * rx.detector_distance()),
               q_end = (last - 2) * h;
  std::vector<double> kinks{2.0 * p.outer * to_q};
  if (p.inner > 0.0)
    for (double v : {p.outer - p.inner, p.outer + p.inner, 2.0 * p.inner})
      kinks.push_back(v * to_q);
  std::vector<double> edges{0.0, q_end};
  for (double k : kinks)
    if (k > 0.0 && k < q_end) edges.push_back(k);
  std::sort(edges.begin(), edges.end());
  // Fastest oscillation of T: the detector disc's plus the point image's (blur and diffraction scale).
  const double bandwidth = r_d + rx.blur_radius() + 4.0 / rx.cutoff(),
               panel_length = kPanelPeriods / bandwidth;
  std::vector<double> node_q(kPanelNodes), node_t(kPanelNodes), weight(kPanelNodes);
  for (std::size_t k = 0; k < kPanelNodes; ++k)  // barycentric weights of the second-kind nodes
    weight[k] = (k % 2 ? -1.0 : 1.0) * ((k == 0 || k + 1 == kPanelNodes) ? 0.5 : 1.0);
  std::size_t t = 2;  // next table node to fill
  for (std::size_t e = 0; e + 1 < edges.size(); ++e) {
    const double a0 = edges[e], b0 = edges[e + 1];
    const std::size_t pieces =
        std::max<std::size_t>(1, checks::saturate(std::ceil((b0 - a0) / panel_length)));
    for (std::size_t piece = 0; piece < pieces; ++piece) {
      const double a = a0 + (b0 - a0) * piece / pieces,
                   b = piece + 1 == pieces ? b0 : a0 + (b0 - a0) * (piece + 1) / pieces;
      std::size_t stop = t;  // table nodes in [a, b] (the last panel takes the end)
      while (stop <= last &&
             ((stop - 2.0) * h <= b || (e + 2 == edges.size() && piece + 1 == pieces)))
        ++stop;
      const bool near_kink =
          (a0 > 0.0 && piece == 0 && e > 0) || (piece + 1 == pieces && e + 2 < edges.size());
      if (near_kink || stop - t <= kPanelNodes) {
        for (; t < stop; ++t) table_[t] = exact((t - 2.0) * h);
        continue;
      }
      for (std::size_t k = 0; k < kPanelNodes; ++k) {
        node_q[k] = 0.5 * (a + b) + 0.5 * (b - a) * std::cos(kPi * k / (kPanelNodes - 1));
        node_t[k] = exact(node_q[k]);
      }
      for (; t < stop; ++t) {
        const double q = (t - 2.0) * h;
        double num = 0.0, den = 0.0;
        std::size_t k = 0;
        for (; k < kPanelNodes; ++k) {
          const double d = q - node_q[k];
          if (d == 0.0) break;
          num += weight[k] / d * node_t[k];
          den += weight[k] / d;
        }
        table_[t] = k < kPanelNodes ? node_t[k] : num / den;
      }
    }
  }
  table_[0] = table_[4];
  table_[1] = table_[3];
}

}  // namespace lidar_overlap::detail
