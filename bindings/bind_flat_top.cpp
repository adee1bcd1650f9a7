// Flat-top phase-plate design: the design comes back as a FlatTopDesign whose arrays are NumPy arrays, the GIL
// released during the design.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <vector>

#include "arrays.hpp"
#include "bind_field.hpp"
#include "interruptible.hpp"
#include "lidar_overlap/beams/flat_top.hpp"

namespace py = pybind11;
using namespace lidar_overlap;

void bind_flat_top(py::module_& m) {
  using D = FlatTopDesign;
  py::class_<D>(m, "FlatTopDesign", "Result of design_flat_top.")
      .def_property_readonly(
          "field", [](const D& d) { return array_from_field(d.transmitted); },
          "W^0.5/m at z = 0: TEM00 amplitude times exp(i phase), n x n.")
      .def_property_readonly(
          "spacing", [](const D& d) { return d.transmitted.spacing; }, "m, of field and phase.")
      .def_property_readonly(
          "phase", [](const D& d) { return square_array(d.phase, d.transmitted.n); },
          "rad, the plate, n x n.")
      .def_property_readonly(
          "target", [](const D& d) { return square_array(d.target, d.transmitted.n); },
          "W/sr, far-field target, n x n (index n/2 is angle 0).")
      .def_property_readonly(
          "far_field", [](const D& d) { return square_array(d.far_field, d.transmitted.n); },
          "W/sr, far-field radiant intensity the plate achieves, n x n.")
      .def_readonly("angular_spacing", &D::angular_spacing, "rad per far-field sample.")
      .def_readonly("edge_width_target", &D::edge_width_target,
                    "rad, 10-90 % edge width asked of the target.")
      .def_property_readonly(
          "history", [](const D& d) { return to_array(d.history); },
          "Amplitude error per iteration.")
      .def_property_readonly(
          "stop", [](const D& d) { return to_string(d.stop); },
          "'converged', 'stagnated' or 'max_iterations'.")
      .def_readonly("monotone", &D::monotone, "The error never rose.")
      .def_readonly("efficiency", &D::efficiency, "Fraction of the power inside the nominal disc.")
      .def_readonly("uniformity_rms", &D::uniformity_rms,
                    "std / mean of the far field over the plateau.")
      .def_readonly("uniformity_pv", &D::uniformity_pv, "(max - min) / mean over the plateau.")
      .def_readonly("edge_width", &D::edge_width, "rad, achieved 10-90 % width.");

  m.def(
      "design_flat_top",
      [](double wavelength, double waist_radius, double angular_diameter, std::size_t grid,
         double samples_per_waist, double edge_width, std::size_t max_iterations, double tolerance,
         double max_error, double power) {
        Interruptible release;
        return design_flat_top(wavelength, waist_radius, angular_diameter,
                               FlatTopOptions{grid, samples_per_waist, edge_width, max_iterations,
                                              tolerance, max_error, power});
      },
      py::arg("wavelength"), py::arg("waist_radius"), py::arg("angular_diameter"), py::arg("grid"),
      py::arg("samples_per_waist"), py::arg("edge_width"), py::arg("max_iterations"),
      py::arg("tolerance"), py::arg("max_error"), py::arg("power"));
}
