// Exact areas of intersections of discs: the circle-circle lens of the paper's Eq. (B19) and its
// generalisation to several discs (the aperture, the detector seen through the lens, the NA cone and
// the obstruction shadow), computed from the boundary arcs with Green's theorem.
#pragma once

#include <cstddef>

#include "lidar_overlap/core/vec2.hpp"

namespace lidar_overlap {

struct Disc {
  Vec2 center;    // m
  double radius;  // m, >= 0
};

// Area (m^2) between a chord and the arc of half-angle `half` (rad) of a circle of radius r (m), without
// cancellation for thin segments.
double segment_area(double r, double half);

// Area (m^2) of the intersection of two discs, Eq. (B19) in a cancellation-free form.
double lens_area(const Disc& a, const Disc& b);

// Area (m^2) of the intersection of n discs (n <= kMaxDiscs).
constexpr std::size_t kMaxDiscs = 6;
double intersection_area(const Disc* discs, std::size_t n);

}  // namespace lidar_overlap
