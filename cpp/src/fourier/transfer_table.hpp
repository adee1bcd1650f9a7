// The receiver's transfer function T(q) = OTF(q) x disc^(q) (m^2 x m^2) of the Parseval sum of the 2-D
// Fourier-optics overlap (overlap_fo.cpp, and the turbulent path's coupling maps in overlap_turbulent.cpp),
// tabulated on [0, q_max] and interpolated: the sum asks for it at every frequency of the padded grid.
// 24 table points per period of its fastest oscillation (detector disc or point-image blur), interpolated
// by quintic (six-point Lagrange) polynomials: G converged to ~3e-7 (cubic needed 128 points for that).
// The table's values come from exact T at Chebyshev nodes, 80 per 16 periods (5 per period instead of 24),
// interpolated to ~1e-13 of T(0): the OTF evaluations, O(defocus phase) each, are what the table costs.
// Internal header, not installed.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "lidar_overlap/core/system.hpp"
#include "core/checks.hpp"
#include "fourier/fo_receiver.hpp"

namespace lidar_overlap::detail {

class TransferTable {
 public:
  // Table of T on [0, q_max] (1/m) for the receiver `rx` of `system`.
  TransferTable(const LidarSystem& system, const FoReceiver& rx, double q_max);

  // T(q) for 0 <= q < q_max.
  double operator()(double q) const {
    const double pos = q * inv_h_;
    // 0 <= pos < nt_ - 3 for q in [0, q_max): a plain conversion (a call per sample costs the sum ~10%).
    const std::size_t j = std::min(static_cast<std::size_t>(pos), nt_ - 4);
    const double* p = &table_[j];  // the six nodes at q/h = j-2 ... j+3
    const double x = pos - j, a = x + 2.0, b = x + 1.0, d = x - 1.0, e = x - 2.0, f = x - 3.0;
    const double ab = a * b, de = d * e, xf = x * f;
    return (ab * (de * (x * p[5] - 10.0 * f * p[2]) + xf * (10.0 * e * p[3] - 5.0 * d * p[4])) +
            de * xf * (5.0 * a * p[1] - b * p[0])) *
           (1.0 / 120.0);
  }

 private:
  std::size_t nt_;
  double inv_h_;
  std::vector<double> table_;
};

}  // namespace lidar_overlap::detail
