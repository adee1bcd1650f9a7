// Zernike polynomials on the unit disc, Noll's single index j >= 1 (Noll 1976): j = 1 piston, 2-3 tilt
// (x, y), 4 defocus, 5-6 astigmatism (45 deg, 0 deg), 7-8 coma (y, x), 9-10 trefoil, 11 spherical, ...
// Normalised to unit RMS over the disc (sqrt(n+1) for m = 0, sqrt(2(n+1)) otherwise), so a coefficient is
// the RMS wavefront of its term and the RMS of a sum is the root of the summed squares.
#pragma once

#include "lidar_overlap/core/vec2.hpp"

namespace lidar_overlap {

struct ZernikeIndex {
  int n = 0;  // radial order
  int m = 0;  // signed azimuthal order: m > 0 cos(m theta), m < 0 sin(|m| theta)
};

// Throws std::invalid_argument naming `parameter` for j < 1 or j > 1000.
ZernikeIndex noll_index(int j, const char* parameter = "j");

// Z_j at the normalised pupil point p (|p| <= 1; the polynomial is evaluated beyond it too).
double zernike(int j, Vec2 p);

// Gradient (dZ/dx, dZ/dy) at p, per unit normalised pupil coordinate.
Vec2 zernike_gradient(int j, Vec2 p);

}  // namespace lidar_overlap
