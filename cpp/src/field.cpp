#include "lidar_overlap/field.hpp"

#include <cmath>

#include "lidar_overlap/checks.hpp"
#include "lidar_overlap/constants.hpp"

namespace lidar_overlap {

void Field::validate() const {
  if (n < 8 || n % 2 != 0) checks::fail("field.n", static_cast<double>(n), "an even grid size >= 8");
  if (values.size() != n * n) checks::fail("field.values", static_cast<double>(values.size()), "n * n values");
  checks::positive("field.spacing", spacing);
  checks::positive("field.wavelength", wavelength);
}

double Field::power() const {
  double sum = 0.0;
  for (const Complex& v : values) sum += std::norm(v);
  return sum * spacing * spacing;
}

Vec2 Field::centroid() const {
  double sum = 0.0, sx = 0.0, sy = 0.0;
  for (std::size_t iy = 0; iy < n; ++iy)
    for (std::size_t ix = 0; ix < n; ++ix) {
      const double e = std::norm(values[iy * n + ix]);
      sum += e;
      sx += e * coordinate(ix);
      sy += e * coordinate(iy);
    }
  return sum > 0.0 ? Vec2{sx / sum, sy / sum} : Vec2{};
}

double Field::beam_radius() const {
  const Vec2 c = centroid();
  double sum = 0.0, s2 = 0.0;
  for (std::size_t iy = 0; iy < n; ++iy)
    for (std::size_t ix = 0; ix < n; ++ix) {
      const double e = std::norm(values[iy * n + ix]);
      const double dx = coordinate(ix) - c.x, dy = coordinate(iy) - c.y;
      sum += e;
      s2 += e * (dx * dx + dy * dy);
    }
  return sum > 0.0 ? std::sqrt(2.0 * s2 / sum) : 0.0;
}

Field Field::gaussian(double wavelength, double waist_radius, std::size_t n, double spacing, Vec2 center,
                      double power) {
  checks::positive("waist_radius", waist_radius);
  checks::positive("power", power);
  checks::finite("center", center);
  Field f{ComplexBuffer(n * n), n, spacing, wavelength};
  f.validate();
  const double amplitude = std::sqrt(2.0 * power / (kPi * waist_radius * waist_radius));
  for (std::size_t iy = 0; iy < n; ++iy)
    for (std::size_t ix = 0; ix < n; ++ix) {
      const double dx = f.coordinate(ix) - center.x, dy = f.coordinate(iy) - center.y;
      f.values[iy * n + ix] = amplitude * std::exp(-(dx * dx + dy * dy) / (waist_radius * waist_radius));
    }
  return f;
}

}  // namespace lidar_overlap
