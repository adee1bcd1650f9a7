// Limits every entry point enforces before it allocates or computes. A request beyond them throws
// std::invalid_argument naming the caller's parameter, its value, the limit and the fix, so no input can
// overflow a size, exhaust memory or start work without end.
#pragma once

#include <cstddef>

namespace lidar_overlap {

// Physical scales. Every length (m) lies in [kMinLength, kMaxLength] (offsets and defocus within
// +-kMaxLength), every angle (rad) within +-kMaxAngle: beyond them derived quantities (areas, Fresnel
// numbers, diffraction-limited divergences) leave double precision long before any lidar does.
inline constexpr double kMinLength = 1e-10;
inline constexpr double kMaxLength = 1e10;
inline constexpr double kMaxAngle = 1.0;

// Power of a field (W): (0, kMaxPower], so that irradiances stay far inside double precision.
inline constexpr double kMaxPower = 1e30;

// Samples per side of any square grid (a further bound under the memory budget below).
inline constexpr std::size_t kMaxGridSide = std::size_t{1} << 16;

// Bytes one call may allocate for its grids and tables. Default: a quarter of the machine's physical memory
// (room for the caller's own copies and for a second call running beside it).
std::size_t max_memory();
// Sets that budget for every later call (0 restores the default). Not meant to change during a call.
void set_max_memory(std::size_t bytes);

// Threads one call may use (the `threads` option; 0 means all cores): at most max(256, 4 x cores).
int max_threads();

}  // namespace lidar_overlap
