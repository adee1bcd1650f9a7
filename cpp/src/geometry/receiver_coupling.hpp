// Paraxial ray geometry of the receiver (paper Appendix B steps 4-6 and Section 4A-4B), written in
// the aperture-stop plane. For a point scatterer P at range z, the aperture points A whose ray
// P -> A reaches the detector form a set bounded by circles whose centres are affine in P:
//   aperture  |A| <= R
//   detector  |m A - P d/z - o_d| <= r_d        (m = 1 + d/z - d/f, d = f + defocus; B14-B20)
//   fibre NA  |A (1/z - 1/f) - P/z| <= tan(asin NA)
//   stop      |A (1 + s/z - s/f) - P s/z| <= r_s   (second stop s behind the lens)
//   shadow    |A (1 - z_obs/z) + P z_obs/z| < r_obs  (blocked by the central obstruction)
// The coupling of P is the area of (aperture ∩ detector ∩ NA) minus its part inside the shadow,
// over the aperture area: the exact form of the paper's circles of confusion and their intersection
// with the detector (B17-B21), which also holds when the shadow leaves the aperture's edge.
// Internal header (the RT engine's coupling of one scatterer), not installed.
#pragma once

#include <cstddef>

#include "lidar_overlap/core/system.hpp"
#include "geometry/circles.hpp"
#include "geometry/coupling_term.hpp"

namespace lidar_overlap {

class Receiver {
 public:
  // Geometry for scatterers at range z (m). The system and z are validated here.
  Receiver(const LidarSystem& system, double z);

  // Fraction of the power that a point scatterer at transverse position p (m) sends into the full,
  // unobstructed aperture that reaches the detector.
  double coupling(Vec2 p) const;

  // The terms whose sum is coupling() for every scatterer within `support` (m) of `center` (m):
  // "passing" and, with an obstruction, "blocked" (negative weight). Where the shadow stays inside the
  // aperture for all those scatterers, the blocked term leaves out the aperture disc, which can give
  // it a centre of symmetry. Returns how many terms were written to `out` (1 or 2).
  std::size_t terms(Vec2 center, double support, CouplingTerm* out) const;

  double range() const { return z_; }

 private:
  double z_;
  double aperture_radius_;
  CouplingTerm passing_;  // aperture ∩ detector ∩ NA ∩ second stop
  CouplingTerm blocked_;  // the same ∩ shadow, negative weight
  bool has_shadow_ = false;
  MovingDisc shadow_{};
};

}  // namespace lidar_overlap
