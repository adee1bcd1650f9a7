// Wavefront aberrations of the receiver (paper Section 3, step 5): Zernike terms for the pupil (the same for
// every scatterer, as Fourier optics' shift-invariant image needs) and Seidel terms that vary with the
// scatterer's field angle (traced by rays). W is an optical path in metres added to the pupil phase as
// exp(2 pi i W / lambda), with the pupil coordinate normalised to the telescope radius D/2. Its transverse ray
// error on the detector plane, d grad W / (D/2), follows from that phase by stationary phase.
#pragma once

#include <vector>

#include "lidar_overlap/core/vec2.hpp"

namespace lidar_overlap {

// A polynomial in the normalised pupil coordinates, W = sum c[p (degree + 1) + q] x^p y^q, for evaluating
// a wavefront on large grids row by row.
struct PupilPolynomial {
  int degree = 0;
  std::vector<double> c;
  // The coefficients of x^p (p = 0 ... degree) along the row y.
  void row(double y, double* out) const;
};

struct Aberrations {
  static constexpr std::size_t kMaxNollIndex =
      231;  // radial order 20: max_gradient samples finely enough
  static constexpr double kMaxCoefficient =
      1e-2;                     // m: a wavefront error of 1 cm is far beyond any receiver
  std::vector<double> zernike;  // m RMS; zernike[j - 1] is Noll term j (pupil/zernike.hpp)
  // Seidel coefficients (m) at the pupil edge and the field edge H = 1: W040 rho^4 + W131 H rho^3 cos +
  // W222 H^2 rho^2 cos^2 + W220 H^2 rho^2 + W311 H^3 rho cos, with cos the angle between pupil point and field.
  double w040 = 0.0, w131 = 0.0, w222 = 0.0, w220 = 0.0, w311 = 0.0;
  double field_radius = 0.0;  // rad, field angle at H = 1; > 0 when a field-dependent term is set

  // Throws std::invalid_argument naming the coefficient for non-finite values, and `field_radius` when a
  // field-dependent term is set without it.
  void validate() const;
  bool none() const;             // no term set: the aberration-free receiver
  bool field_dependent() const;  // W131, W222, W220 or W311 set
  // W (m) at normalised pupil point p for a scatterer seen at field angle `field` (rad, vector).
  double wavefront(Vec2 p, Vec2 field = {}) const;
  // grad W (m per unit normalised pupil coordinate) at p.
  Vec2 gradient(Vec2 p, Vec2 field = {}) const;
  // max |grad W| over the unit pupil (sampled on a polar grid fine enough for polynomials of order <= 20).
  double max_gradient(Vec2 field = {}) const;
  // The field-independent part (Zernike terms and W040) as a polynomial; empty (degree -1) when the Zernike
  // terms go beyond radial order 16, where the expansion loses digits to cancellation.
  PupilPolynomial pupil_polynomial() const;
};

}  // namespace lidar_overlap
