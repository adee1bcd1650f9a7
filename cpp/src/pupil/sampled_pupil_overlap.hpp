// The Fourier-optics overlap through a sampled pupil (overlap_fo_aberrated.cpp): G = G_0 + the Parseval sum of
// the change of the sampled OTF. Shared by the aberrated receiver and the masked one (aperture masks cut the
// sampled pupil to their sectors; aperture_mask.cpp). Internal header, not installed.
#pragma once

#include <string>
#include <vector>

#include "lidar_overlap/pupil/overlap_fo_aberrated.hpp"
#include "geometry/sector_area.hpp"

namespace lidar_overlap::detail {

// G at every range for the pupil with `aberrations` (field-independent, validated) cut to `mask` (sectors in the
// aperture plane; empty: none). `name` names the engine in value errors.
FoAberratedOverlap overlap_fo_sampled(const LidarSystem& system, const Aberrations& aberrations,
                                      const std::vector<AnnularSector>& mask,
                                      const std::vector<double>& ranges,
                                      const FoAberratedOptions& options, const std::string& name);

}  // namespace lidar_overlap::detail
