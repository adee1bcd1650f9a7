// Exact area of an intersection of discs restricted to an annular sector of the aperture plane (the
// aperture masks of lidar_overlap/pupil/aperture_mask.hpp). Internal header, not installed.
#pragma once

#include <cstddef>

#include "geometry/circles.hpp"

namespace lidar_overlap {

// Points at polar angle in [start, start + span] (rad, from +x towards +y, 0 < span <= 2 pi) and radius in
// [inner, outer] (m, 0 <= inner < outer) about the origin.
struct AnnularSector {
  double start, span, inner, outer;
};

// Area (m^2) of (discs[0] ∩ ... ∩ discs[n-1]) ∩ sector, n <= kMaxDiscs. Along each ray from the origin a
// disc is one interval of radii; between the angles where the active interval ends can change (the
// sector's edges, the tangents from the origin, the crossings of any two circles including the sector's
// arcs) the region is bounded by one arc below and one above, and the swept area of an arc is a
// triangle plus or minus a circular segment: exact to rounding, with no quadrature.
double sector_intersection_area(const Disc* discs, std::size_t n, const AnnularSector& sector);

// Whether p (m) lies in the sector, and a lower bound of its distance (m) to the sector's boundary (for
// sampling a masked pupil: pixels nearer than their half-diagonal are sub-sampled).
bool sector_contains(const AnnularSector& sector, Vec2 p);
double sector_boundary_distance(const AnnularSector& sector, Vec2 p);

}  // namespace lidar_overlap
