// Fields cross the boundary as (complex array, spacing, wavelength); the C++ Field owns an aligned copy.
#include "bind_field.hpp"
#include "interruptible.hpp"
#include "core/checks.hpp"

#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cstring>

namespace py = pybind11;
using namespace lidar_overlap;

Field field_from_array(const ComplexArray& values, double spacing, double wavelength) {
  if (values.ndim() != 2 || values.shape(0) != values.shape(1))
    throw std::invalid_argument("values: expected a square (n, n) complex array");
  Field f;
  f.n = static_cast<std::size_t>(values.shape(0));
  f.spacing = spacing;
  f.wavelength = wavelength;
  f.values.resize(f.n * f.n);
  std::memcpy(f.values.data(), values.data(), f.n * f.n * sizeof(Complex));
  f.validate();
  return f;
}

ComplexArray array_from_field(const Field& f) {
  ComplexArray out({f.n, f.n});
  std::memcpy(out.mutable_data(), f.values.data(), f.n * f.n * sizeof(Complex));
  return out;
}

py::array_t<double> square_array(const std::vector<double>& values, std::size_t n) {
  py::array_t<double> out({n, n});
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

void bind_field(py::module_& m) {
  m.def(
      "field_moments",
      [](const ComplexArray& values, double spacing, double wavelength) {
        const Field f = field_from_array(values, spacing, wavelength);
        double power, radius;
        Vec2 c;
        {
          Interruptible release;
          power = f.power();
          c = f.centroid();
          radius = f.beam_radius();
        }
        return py::make_tuple(power, std::array<double, 2>{c.x, c.y}, radius);
      },
      py::arg("values"), py::arg("spacing"), py::arg("wavelength"));
  m.def(
      "gaussian_field",
      [](double wavelength, double waist_radius, std::size_t n, double spacing,
         std::array<double, 2> center, double power) {
        checks::grid("n", n, sizeof(Complex), 2);  // the core's field and the NumPy copy returned
        Field f;
        {
          Interruptible release;  // n^2 exponentials: seconds for the largest grids
          f = Field::gaussian(wavelength, waist_radius, n, spacing, {center[0], center[1]}, power);
        }
        return array_from_field(f);
      },
      py::arg("wavelength"), py::arg("waist_radius"), py::arg("n"), py::arg("spacing"),
      py::arg("center"), py::arg("power"));
}
