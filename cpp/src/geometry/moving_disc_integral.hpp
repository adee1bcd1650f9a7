// The beam integral of a masked coupling term with one moving disc, done in the aperture plane as a 1-D
// integral (docs/rt_method.md, "Masks"). Internal header, not installed.
//
// The term is weight * area(F ∩ disc(X, r)), with F the fixed discs cut to the mask and X = s P + b moving
// with the scatterer P. Over the Gaussian beam (centre c, 1/e^2 radius w) X is Gaussian: mean mu = s c + b,
// per-axis sigma = |s| w / 2. An aperture point a is covered with probability K(|a - mu|), K(q) = 1 -
// Q1(q / sigma, r / sigma) (Marcum's Q), so the term's mean is the integral of K over F. In polar
// coordinates about mu, and by parts with Lambda(q) = area(F ∩ disc(mu, q)) (exact, sector_area.hpp):
//   mean = weight int_0^inf Lambda(q) k(q) dq,  k = -K' = (r / sigma^2) exp(-(q^2 + r^2) / 2 sigma^2) I1(q r / sigma^2),
// since dQ1(a, b)/da = b exp(-(a^2 + b^2) / 2) I1(a b). One adaptive integral in q whatever the mask, where
// the scatterer-plane form needs one over directions as well (tens of times the couplings).
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "geometry/beam_integral.hpp"
#include "geometry/coupling_term.hpp"
#include "geometry/sector_area.hpp"

namespace lidar_overlap::beam_integral {

// The term's beam mean through each mask (a union of sectors) by the 1-D form above, each to `tolerance`
// (absolute), the masks sharing the nodes; nullopt when the term does not have exactly one moving disc (the
// receiver's terms already leave out a disc that holds the whole aperture, such as a wide NA cone), or has a
// gate (a boundary that depends on the scatterer only), or more fixed discs than sector_intersection_area
// takes: the caller then integrates in the scatterer plane.
std::optional<std::vector<RangeResult>> moving_disc_integral(
    const CouplingTerm& term, const std::vector<std::vector<AnnularSector>>& masks, Vec2 center,
    double w, double tolerance, std::size_t max_segments);

}  // namespace lidar_overlap::beam_integral
