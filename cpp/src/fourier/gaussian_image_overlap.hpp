// The radial Fourier-optics integral of lidar_overlap/fourier/overlap_fo_radial.hpp at one range, shared by
// overlap_fo_radial and overlap_fo_aberrated (its aberration-free part). Internal header, not installed.
#pragma once

#include <cstddef>
#include <string>

#include "lidar_overlap/core/system.hpp"

namespace lidar_overlap {

// The integral of overlap_fo_radial.hpp at one range z (m), named `parameter` in errors; adds the number of
// OTF evaluations to *evaluations when given. Throws std::invalid_argument where it would need more than kMaxRadialPanels
// panels (a detector, blur or offset of very many image resolutions: the geometric regime).
inline constexpr std::size_t kMaxRadialPanels = std::size_t{1} << 18;
double gaussian_image_overlap(const LidarSystem& system, double z, double periods_per_panel = 4.0,
                              std::size_t* evaluations = nullptr,
                              const std::string& parameter = "z");

}  // namespace lidar_overlap
