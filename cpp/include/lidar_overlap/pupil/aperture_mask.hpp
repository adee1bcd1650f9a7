// Aperture masks: the telecover test of EARLINET's quality assurance (Freudenthaler et al., 2018, AMT 11,
// 4713) covers all of the receiver's aperture but one sector and compares the signals. A mask is a union of
// annular sectors of the aperture stop; G stays normalised to the full, unobstructed aperture, so the
// G's of the parts of a partition add up to the full G.
#pragma once

#include <optional>
#include <vector>

#include "lidar_overlap/pupil/overlap_fo_aberrated.hpp"
#include "lidar_overlap/core/system.hpp"
#include "lidar_overlap/geometry/overlap_rt.hpp"

namespace lidar_overlap {

// Aperture points at polar angle in [start_angle, stop_angle] (rad, measured from +x towards +y in the
// aperture plane, the frame of the beam's offset and tilt) and radius in [inner_radius, outer_radius] (m).
struct Sector {
  double start_angle = 0.0;
  double stop_angle = 0.0;             // > start_angle, at most 2 pi beyond it
  double inner_radius = 0.0;           // m, >= 0
  std::optional<double> outer_radius;  // m, at most D/2; empty: the aperture's edge D/2
};

struct ApertureMask {
  std::vector<Sector> sectors;  // a union: at least one, no two overlapping

  // Each sector finite and within the aperture (outer radius beyond the obstruction's radius, so that
  // something is left), no two overlapping (in angle and in radius; touching is allowed). Throws
  // std::invalid_argument naming sectors[i].
  void validate(const Telescope& telescope) const;
};

// Most sectors one mask may hold (each multiplies the cost of a coupling).
inline constexpr std::size_t kMaxMaskSectors = 64;

// G of the masked receiver at every range (m): the exact coupling of each scatterer restricted to the mask
// (the area of the aperture points whose rays reach the detector, pass the obstruction and the NA cone, and
// lie in the mask, over pi R^2), integrated over the Gaussian beam. Where the detector disc is the only
// boundary that moves with the scatterer (an NA cone that bounds nothing, obstruction absent or in the
// aperture plane), one 1-D integral of exact areas against the Marcum-Q kernel per range
// (docs/telecover.md); otherwise the beam integral of overlap_rt, radial for full rings about a centre of
// symmetry, over directions too for sectors (tens of times the couplings). Thread-safe; throws
// std::invalid_argument for an invalid system, range, mask or option.
RtOverlap overlap_rt(const LidarSystem& system, const std::vector<double>& ranges,
                     const ApertureMask& mask, const RtOptions& options = {});

// Most masks one call of the many-mask overlap_rt may hold.
inline constexpr std::size_t kMaxMasks = 64;

// G through each of several masks (the sectors of a telecover test) at every range, in one pass: where the
// detector disc is the only moving boundary (as above) the masks share the beam integral's nodes, kernel and
// geometry (Table 1's four quadrants: 3.8 full curves); otherwise each mask is traced as above. Entry i is
// masks[i]'s G to the same tolerance (not bit for bit the one-mask call: the nodes differ). Throws
// std::invalid_argument as above, naming masks[i], and for 0 or more than kMaxMasks masks.
std::vector<RtOverlap> overlap_rt(const LidarSystem& system, const std::vector<double>& ranges,
                                  const std::vector<ApertureMask>& masks,
                                  const RtOptions& options = {});

// The Fourier-optics G through the mask (Gaussian beams): the sampled pupil of overlap_fo_aberrated cut to the
// mask, its OTF by FFT, and G = G_0 + sum_q [OTF_masked(q) - OTF_full(q)] K^(q) dq^2 / (pi R^2) with G_0 the exact
// radial full-aperture G. Diffraction couples the sectors: the parts of a partition add up to the full G only
// to the diffraction at their edges. Throws std::invalid_argument as overlap_fo_aberrated, and for the mask.
FoAberratedOverlap overlap_fo(const LidarSystem& system, const std::vector<double>& ranges,
                              const ApertureMask& mask, const FoAberratedOptions& options = {});

// Coupling of one point scatterer at (position, z) (m) through the mask, over the power it sends into the
// full, unobstructed aperture.
double emitter_coupling_rt(const LidarSystem& system, double z, Vec2 position,
                           const ApertureMask& mask);

}  // namespace lidar_overlap
