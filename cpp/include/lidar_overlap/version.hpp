// Library version, kept equal to the CMake project version and the Python package version.
#pragma once

namespace lidar_overlap {
inline constexpr const char* kVersion = "0.1.0";
}
