// Flat-top phase-plate design: arrays come back as NumPy arrays, the GIL released during the design.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <vector>

#include "bind_field.hpp"
#include "interruptible.hpp"
#include "lidar_overlap/beams/flat_top.hpp"

namespace py = pybind11;
using namespace lidar_overlap;

void bind_flat_top(py::module_& m) {
  m.def(
      "design_flat_top",
      [](double wavelength, double waist_radius, double angular_diameter, std::size_t grid, double samples_per_waist,
         double edge_width, std::size_t max_iterations, double tolerance, double max_error, double power) {
        FlatTopDesign d;
        {
          Interruptible release;
          d = design_flat_top(wavelength, waist_radius, angular_diameter,
                              FlatTopOptions{grid, samples_per_waist, edge_width, max_iterations, tolerance, max_error, power});
        }
        const std::size_t n = d.transmitted.n;
        py::dict out;
        out["field"] = array_from_field(d.transmitted);
        out["spacing"] = d.transmitted.spacing;
        out["phase"] = square_array(d.phase, n);
        out["target"] = square_array(d.target, n);
        out["far_field"] = square_array(d.far_field, n);
        out["angular_spacing"] = d.angular_spacing;
        out["edge_width_target"] = d.edge_width_target;
        out["history"] = py::array_t<double>(d.history.size(), d.history.data());
        out["stop"] = to_string(d.stop);
        out["monotone"] = d.monotone;
        out["efficiency"] = d.efficiency;
        out["uniformity_rms"] = d.uniformity_rms;
        out["uniformity_pv"] = d.uniformity_pv;
        out["edge_width"] = d.edge_width;
        return out;
      },
      py::arg("wavelength"), py::arg("waist_radius"), py::arg("angular_diameter"), py::arg("grid"),
      py::arg("samples_per_waist"), py::arg("edge_width"), py::arg("max_iterations"), py::arg("tolerance"),
      py::arg("max_error"), py::arg("power"));
}
