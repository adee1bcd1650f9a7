#include "fourier/transfer_table.hpp"

#include <cmath>

#include "fourier/otf.hpp"

namespace lidar_overlap::detail {

TransferTable::TransferTable(const LidarSystem& system, const FoReceiver& rx, double q_max) {
  const double period = 1.0 / std::max({system.detector.radius, rx.blur_radius(), 1.0 / rx.cutoff()});
  nt_ = std::min<std::size_t>(1 << 16, 6 + checks::saturate(24.0 * q_max / period));
  const double h = q_max / (nt_ - 3);
  inv_h_ = 1.0 / h;
  table_.resize(nt_ + 3);
  for (std::size_t t = 0; t < table_.size(); ++t) {
    const double q = std::abs(static_cast<double>(t) - 2.0) * h;  // two points before 0: the even extension
    table_[t] = rx.otf(q) * disc_transform(system.detector.radius, q);
  }
}

}  // namespace lidar_overlap::detail
