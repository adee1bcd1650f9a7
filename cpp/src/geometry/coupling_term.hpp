// One term of a scatterer's coupling: the area of an intersection of discs in the aperture plane
// whose centres move linearly with the scatterer position P, over the aperture area. The receiver's
// coupling is "rays passing" minus "rays passing but blocked by the obstruction" (receiver_coupling.hpp).
#pragma once

#include <array>
#include <cstddef>
#include <optional>

#include "lidar_overlap/core/vec2.hpp"
#include "geometry/circles.hpp"

namespace lidar_overlap {

// Aperture points A with |A - (scale P + shift)| <= radius.
struct MovingDisc {
  double scale;
  Vec2 shift;
  double radius;
  Disc at(Vec2 p) const { return {scale * p + shift, radius}; }
};

// |scale P + shift| <= radius, independent of A: a boundary circle whose A-coefficient vanished
// (e.g. the detector exactly in focus for this range). Closed gates make the term zero.
struct Gate {
  double scale;
  Vec2 shift;
  double radius;
  bool open(Vec2 p) const { return norm(scale * p + shift) <= radius; }
};

struct CouplingTerm {
  // aperture, detector, NA cone, second stop, obstruction shadow, aperture mask
  static constexpr std::size_t kMaxMoving = 6, kMaxGates = 3;
  std::array<MovingDisc, kMaxMoving> discs{};
  std::size_t n_discs = 0;
  std::array<Gate, kMaxGates> gates{};
  std::size_t n_gates = 0;
  double weight = 1.0;  // sign / (pi R^2)

  void add(const MovingDisc& d) { discs[n_discs++] = d; }
  void add(const Gate& g) { gates[n_gates++] = g; }

  // weight * area of the intersection of the discs for a scatterer at p (0 if a gate is closed).
  double operator()(Vec2 p) const;

  // Circles in the scatterer plane on which the term has a kink: two of its boundary circles become
  // tangent, or a gate switches. Writes at most `capacity`; returns how many.
  std::size_t kink_circles(Disc* out, std::size_t capacity) const;

  // A point S such that the term depends on |P - S| only (every pair of disc centres differs by a
  // multiple of P - S; the area is translation invariant), if there is one.
  std::optional<Vec2> symmetry_center() const;
};

}  // namespace lidar_overlap
