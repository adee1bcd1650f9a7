#include "lidar_overlap/fourier/field.hpp"

#include <cmath>

#include "lidar_overlap/core/limits.hpp"
#include "core/cancel_every.hpp"
#include "core/checks.hpp"
#include "core/constants.hpp"
#include "fourier/zeroed_buffer.hpp"

namespace lidar_overlap {

void Field::validate() const {
  if (n < 8 || n % 2 != 0 || n > kMaxGridSide)
    checks::fail("field.n", static_cast<double>(n),
                 "an even grid size from 8 to " + std::to_string(kMaxGridSide));
  if (values.size() != n * n)
    checks::fail("field.values", static_cast<double>(values.size()), "n * n values");
  checks::length("field.spacing", spacing);
  checks::length("field.wavelength", wavelength);
}

double Field::power() const {
  double sum = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    detail::cancellation_point_every(i);  // a 16384^2 field has 2.7e8 samples
    sum += std::norm(values[i]);
  }
  return sum * spacing * spacing;
}

Vec2 Field::centroid() const {
  double sum = 0.0, sx = 0.0, sy = 0.0;
  for (std::size_t iy = 0; iy < n; ++iy) {
    detail::cancellation_point();  // once per row: a 16384^2 field takes seconds on a busy core
    for (std::size_t ix = 0; ix < n; ++ix) {
      const double e = std::norm(values[iy * n + ix]);
      sum += e;
      sx += e * coordinate(ix);
      sy += e * coordinate(iy);
    }
  }
  return sum > 0.0 ? Vec2{sx / sum, sy / sum} : Vec2{};
}

double Field::beam_radius() const {
  const Vec2 c = centroid();
  double sum = 0.0, s2 = 0.0;
  for (std::size_t iy = 0; iy < n; ++iy) {
    detail::cancellation_point();
    for (std::size_t ix = 0; ix < n; ++ix) {
      const double e = std::norm(values[iy * n + ix]);
      const double dx = coordinate(ix) - c.x, dy = coordinate(iy) - c.y;
      sum += e;
      s2 += e * (dx * dx + dy * dy);
    }
  }
  return sum > 0.0 ? std::sqrt(2.0 * s2 / sum) : 0.0;
}

Field Field::gaussian(double wavelength, double waist_radius, std::size_t n, double spacing,
                      Vec2 center, double power) {
  checks::length("wavelength", wavelength);
  checks::length("waist_radius", waist_radius);
  checks::length("spacing", spacing);
  if (!(power > 0.0 && power <= kMaxPower))
    checks::fail("power", power, "a power > 0 and at most 1e30 W");
  checks::coordinate("center", center);
  if (n < 8 || n % 2 != 0) checks::fail("n", static_cast<double>(n), "an even grid size >= 8");
  checks::grid("n", n, sizeof(Complex));
  Field f{detail::zeroed_buffer(n * n), n, spacing, wavelength};
  f.validate();
  const double amplitude = std::sqrt(2.0 * power / (kPi * waist_radius * waist_radius));
  for (std::size_t iy = 0; iy < n; ++iy) {
    detail::cancellation_point();  // n^2 exponentials
    for (std::size_t ix = 0; ix < n; ++ix) {
      const double dx = f.coordinate(ix) - center.x, dy = f.coordinate(iy) - center.y;
      f.values[iy * n + ix] =
          amplitude * std::exp(-(dx * dx + dy * dy) / (waist_radius * waist_radius));
    }
  }
  return f;
}

}  // namespace lidar_overlap
