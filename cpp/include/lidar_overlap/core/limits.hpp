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

// The smallest absolute tolerance on G: G sums thousands of O(1) terms in double precision, whose round-off
// (~1e-16 each) no integral resolves below it; a smaller one only runs every integral to its segment limit.
inline constexpr double kMinTolerance = 1e-14;

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
//
// Threading contract. Each overlap call runs its ranges (or realisations) on an OpenMP team of `threads`
// threads; 0 means all cores for that call alone, or one thread for a second after a team of this process
// started late on a busy machine (docs/reliability.md, "Thread policy"). Calls are thread-safe, so a program may call from several
// threads of its own, but N callers that each pass 0 run N teams of all cores at once: such callers pass
// threads = 1 (the call then runs on the caller's thread alone, also inside the caller's own OpenMP team)
// or their share of the cores. Results do not depend on `threads` (tests/cpp/test_threading_contract.cpp).
// propagate, design_flat_top and point_image have no `threads` option: on grids from 256 x 256 they use
// the calling thread's OpenMP team size (omp_set_num_threads in that thread, or OMP_NUM_THREADS), with the
// same policy as threads = 0, except that transforms from 1024 x 1024 keep that team on a busy machine.
int max_threads();

}  // namespace lidar_overlap
