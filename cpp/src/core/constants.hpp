// Mathematical constants shared by the core.
#pragma once

namespace lidar_overlap {
inline constexpr double kPi = 3.14159265358979323846;
}
