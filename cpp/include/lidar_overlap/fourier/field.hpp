// A sampled scalar optical field U(x, y) (paper Section 2B): n x n complex values on a square grid of
// the given spacing, centred so that index n/2 is x = 0 (x_i = (i - n/2) spacing). |U|^2 is the
// irradiance in W/m^2, so the power is sum |U|^2 spacing^2.
#pragma once

#include <cstddef>

#include "lidar_overlap/core/vec2.hpp"
#include "lidar_overlap/fourier/complex_buffer.hpp"

namespace lidar_overlap {

struct Field {
  ComplexBuffer values;  // row-major, values[iy * n + ix]
  std::size_t n = 0;
  double spacing = 0.0;     // m
  double wavelength = 0.0;  // m

  // Throws std::invalid_argument naming the first invalid member (n even >= 8, sizes > 0).
  void validate() const;

  double coordinate(std::size_t i) const { return (static_cast<double>(i) - 0.5 * n) * spacing; }
  double power() const;        // W
  Vec2 centroid() const;       // m, irradiance-weighted centre
  double beam_radius() const;  // m, sqrt(2 (var_x + var_y)) about the centroid (D4sigma/2)

  // TEM00 beam at its waist, flat phase, total power `power` (W), centred at `center` (m).
  static Field gaussian(double wavelength, double waist_radius, std::size_t n, double spacing,
                        Vec2 center = {}, double power = 1.0);
};

}  // namespace lidar_overlap
