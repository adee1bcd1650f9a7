// The turbulent FO path's two propagation schemes, transmit only and both paths, called by
// overlap_fo_turbulent (internal header, not installed).
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "lidar_overlap/atmosphere/overlap_turbulent.hpp"
#include "lidar_overlap/atmosphere/phase_screen.hpp"
#include "lidar_overlap/core/system.hpp"
#include "atmosphere/coupling_map.hpp"
#include "atmosphere/segment_plan.hpp"

namespace lidar_overlap::detail {

using ScreenGenerators = std::vector<std::unique_ptr<PhaseScreenGenerator>>;

// The rows of a part of `realizations` draws at `n_ranges` ranges, zero until computed.
TurbulentOverlap zero_rows(std::size_t realizations, std::size_t n_ranges, bool both);

// Both paths (TurbulencePaths::both), atmosphere/both_paths.cpp.
TurbulentOverlap both_paths(const LidarSystem& system, const std::vector<double>& ranges,
                            const TurbulenceOptions& o, int threads, const TurbulentPlan& plan,
                            const ScreenGenerators& generators, double dx0);

// The coupling map of each range for the transmit-only path, atmosphere/transmit_path.cpp.
std::vector<std::unique_ptr<CouplingMap>> coupling_maps(const LidarSystem& system,
                                                        const std::vector<double>& ranges,
                                                        const Cn2Profile& atmosphere,
                                                        const TurbulenceOptions& o, int threads,
                                                        const std::vector<double>& range_spacing);

// The transmit-only path (TurbulencePaths::transmit), atmosphere/transmit_path.cpp.
TurbulentOverlap transmit_path(const LidarSystem& system, const std::vector<double>& ranges,
                               const TurbulenceOptions& o, int threads, const TurbulentPlan& plan,
                               const ScreenGenerators& generators,
                               const std::vector<std::unique_ptr<CouplingMap>>& maps, double dx0);

}  // namespace lidar_overlap::detail
