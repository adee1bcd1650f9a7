// Paraxial ray geometry of the receiver (paper Appendix B steps 4-6 and Section 4A-4B), written in
// the aperture-stop plane. For a point scatterer P at range z, the aperture points A whose ray
// P -> A reaches the detector form a set bounded by circles whose centres are affine in P:
//   aperture  |A| <= R
//   detector  |m A - P d/z - o_d| <= r_d        (m = 1 + d/z - d/f, d = f + defocus; B14-B20)
//   fibre NA  |A (1/z - 1/f) - P/z| <= tan(asin NA)
//   shadow    |A (1 - z_obs/z) + P z_obs/z| < r_obs  (blocked by the central obstruction)
// The coupling of P is the area of (aperture ∩ detector ∩ NA) minus its part inside the shadow,
// over the aperture area: the exact form of the paper's circles of confusion and their intersection
// with the detector (B17-B21), which also holds when the shadow leaves the aperture's edge.
#pragma once

#include <array>
#include <cstddef>
#include <optional>

#include "lidar_overlap/circles.hpp"
#include "lidar_overlap/system.hpp"

namespace lidar_overlap {

// Eq. (5): range (m) best focused on a detector displaced by `defocus` (m) behind the focal plane.
// Infinite for defocus = 0; defocus must be >= 0.
double optimal_focus_range(double focal_length, double defocus);

class Receiver {
 public:
  // Geometry for scatterers at range z (m). The system and z are validated here.
  Receiver(const LidarSystem& system, double z);

  // Fraction of the power that a point scatterer at transverse position p (m) sends into the full,
  // unobstructed aperture that reaches the detector.
  double coupling(Vec2 p) const;

  // Circles in the scatterer plane on which coupling() has a kink: where two boundary circles in the
  // aperture plane become tangent, or a degenerate constraint switches. Writes at most `capacity`.
  std::size_t kink_circles(Disc* out, std::size_t capacity) const;

  // A point S about which coupling() is rotationally symmetric (every boundary circle's centre is
  // proportional to P - S), if there is one: then G needs only a radial integral around S.
  std::optional<Vec2> symmetry_center() const;

  // Where the ray from scatterer p through aperture point a meets the detector plane (m).
  Vec2 detector_hit(Vec2 p, Vec2 a) const;

  double range() const { return z_; }
  double aperture_radius() const { return aperture_radius_; }

 private:
  // |scale P + shift - A| <= radius, a disc of aperture points that moves with the scatterer.
  struct MovingDisc {
    double scale;
    Vec2 shift;
    double radius;
    Disc at(Vec2 p) const { return {scale * p + shift, radius}; }
  };
  // |scale P + shift| <= radius: a constraint that does not depend on A (a boundary circle that
  // degenerated because its A-coefficient vanished, e.g. the detector exactly in focus for z).
  struct Gate {
    double scale;
    Vec2 shift;
    double radius;
  };

  double z_;
  double aperture_radius_;
  double detector_distance_;  // d = f + defocus
  double focal_length_;
  Vec2 detector_offset_;
  std::array<MovingDisc, 3> passing_{};  // aperture, detector, NA
  std::size_t n_passing_ = 0;
  MovingDisc shadow_{};
  bool has_shadow_ = false;
  std::array<Gate, 2> gates_{};
  std::size_t n_gates_ = 0;
};

}  // namespace lidar_overlap
