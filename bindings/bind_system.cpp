// System model structs. The Python dataclasses in lidar_overlap/system.py build these; the C++
// validate() methods are the single place where parameter ranges are checked.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "lidar_overlap/core/system.hpp"

namespace py = pybind11;
using namespace lidar_overlap;

namespace {
Vec2 vec2(const std::array<double, 2>& a) { return {a[0], a[1]}; }

WidthLaw width_law(const std::string& name) {
  if (name == "gaussian") return WidthLaw::gaussian;
  if (name == "linear") return WidthLaw::linear;
  throw std::invalid_argument("beam.width_law = '" + name +
                              "' is invalid: expected 'gaussian' or 'linear'");
}
}  // namespace

void bind_system(py::module_& m) {
  py::class_<GaussianBeam>(m, "GaussianBeam")
      .def(py::init([](double wavelength, double waist_radius, std::optional<double> divergence,
                       std::array<double, 2> offset, std::array<double, 2> tilt,
                       const std::string& law) {
             GaussianBeam b{wavelength,   waist_radius, divergence,
                            vec2(offset), vec2(tilt),   width_law(law)};
             b.validate();
             return b;
           }),
           py::arg("wavelength"), py::arg("waist_radius"), py::arg("divergence"), py::arg("offset"),
           py::arg("tilt"), py::arg("width_law"))
      .def("half_angle_divergence", &GaussianBeam::half_angle_divergence)
      .def("radius", py::vectorize(&GaussianBeam::radius), py::arg("z"));

  py::class_<Telescope>(m, "Telescope")
      .def(py::init([](double diameter, double focal_length, double obstruction_radius,
                       double obstruction_distance) {
             Telescope t{diameter, focal_length, obstruction_radius, obstruction_distance};
             t.validate();
             return t;
           }),
           py::arg("diameter"), py::arg("focal_length"), py::arg("obstruction_radius"),
           py::arg("obstruction_distance"));

  py::class_<Detector>(m, "Detector")
      .def(py::init([](double radius, double defocus, std::array<double, 2> offset,
                       std::optional<double> numerical_aperture, std::optional<double> stop_radius,
                       double stop_distance) {
             Detector d{radius,      defocus,      vec2(offset), numerical_aperture,
                        stop_radius, stop_distance};
             d.validate();
             return d;
           }),
           py::arg("radius"), py::arg("defocus"), py::arg("offset"), py::arg("numerical_aperture"),
           py::arg("stop_radius") = std::nullopt, py::arg("stop_distance") = 0.0)
      .def_static(
          "from_fov",
          [](double fov, double focal_length, double defocus, std::array<double, 2> offset,
             std::optional<double> na) {
            return Detector::from_fov(fov, focal_length, defocus, vec2(offset), na);
          },
          py::arg("fov"), py::arg("focal_length"), py::arg("defocus"), py::arg("offset"),
          py::arg("numerical_aperture"))
      .def_readonly("radius", &Detector::radius);

  py::class_<LidarSystem>(m, "LidarSystem")
      .def(py::init([](const GaussianBeam& b, const Telescope& t, const Detector& d) {
             LidarSystem s{b, t, d};
             s.validate();
             return s;
           }),
           py::arg("beam"), py::arg("telescope"), py::arg("detector"))
      .def("is_axisymmetric", &LidarSystem::is_axisymmetric)
      .def(
          "validate_ranges",
          [](const LidarSystem& s, const std::vector<double>& ranges) {
            for (std::size_t i = 0; i < ranges.size(); ++i)
              s.validate_range(ranges[i], "ranges[" + std::to_string(i) + "]");
          },
          py::arg("ranges"),
          "Throws ValueError naming ranges[i] for a range out of [1e-10, 1e10] m or inside the "
          "obstruction distance.");
}
