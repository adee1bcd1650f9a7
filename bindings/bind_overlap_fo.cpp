// Fourier-optics overlap: options and results as classes; the GIL is released around the compute only.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <vector>

#include "arrays.hpp"
#include "bind_field.hpp"
#include "interruptible.hpp"
#include "options.hpp"
#include "lidar_overlap/fourier/overlap_fo.hpp"
#include "lidar_overlap/fourier/overlap_fo_radial.hpp"

namespace py = pybind11;
using namespace lidar_overlap;

void bind_overlap_fo(py::module_& m) {
  bind_options(
      m, "FoOptions", "Options of overlap_fo and overlap_fo_field (which uses the last two only).",
      option("beam_grid", &FoOptions::beam_grid, "Samples per side of the TEM00 field."),
      option("beam_window", &FoOptions::beam_window, "Its window, in waist radii."),
      option("max_spectrum_grid", &FoOptions::max_spectrum_grid,
             "Cap on the zero-padded beam spectrum."),
      option("threads", &FoOptions::threads, "OpenMP threads across ranges; 0: all cores."));
  bind_options(
      m, "RadialFoOptions", "Options of overlap_fo_radial.",
      option("periods_per_panel", &RadialFoOptions::periods_per_panel,
             "Panel length in periods of the fastest oscillation (24 nodes each)."),
      option("threads", &RadialFoOptions::threads, "OpenMP threads across ranges; 0: all cores."));

  py::class_<FoOverlap>(m, "FoOverlap",
                        "Result of overlap_fo and overlap_fo_field: one entry per range.")
      .def_property_readonly("overlap", [](const FoOverlap& r) { return to_array(r.overlap); })
      .def_property_readonly(
          "beam_reports", [](const FoOverlap& r) { return r.beam_reports; },
          "The transmitted field's propagation to each range.")
      .def_property_readonly(
          "spectrum_grid", [](const FoOverlap& r) { return to_array(r.spectrum_grid); },
          "Padded spectrum size used at each range.");
  py::class_<RadialFoOverlap>(m, "RadialFoOverlap",
                              "Result of overlap_fo_radial: one entry per range.")
      .def_property_readonly("overlap",
                             [](const RadialFoOverlap& r) { return to_array(r.overlap); })
      .def_property_readonly(
          "evaluations", [](const RadialFoOverlap& r) { return to_array(r.evaluations); },
          "OTF evaluations per range.");

  m.def(
      "overlap_fo",
      [](const LidarSystem& system, const std::vector<double>& ranges, const FoOptions& options) {
        Interruptible release;
        return overlap_fo(system, ranges, options);
      },
      py::arg("system"), py::arg("ranges"), py::arg("options") = FoOptions{});

  // Any transmitted field (flat-top, annular, vortex, ...): the field's own grid replaces beam_grid.
  m.def(
      "overlap_fo_field",
      [](const LidarSystem& system, const std::vector<double>& ranges, const ComplexArray& values,
         double spacing, double wavelength, const FoOptions& options) {
        const Field transmitted = field_from_array(values, spacing, wavelength);
        Interruptible release;
        return overlap_fo(system, ranges, transmitted, options);
      },
      py::arg("system"), py::arg("ranges"), py::arg("values"), py::arg("spacing"),
      py::arg("wavelength"), py::arg("options") = FoOptions{});

  m.def(
      "overlap_fo_radial",
      [](const LidarSystem& system, const std::vector<double>& ranges,
         const RadialFoOptions& options) {
        Interruptible release;
        return overlap_fo_radial(system, ranges, options);
      },
      py::arg("system"), py::arg("ranges"), py::arg("options") = RadialFoOptions{});

  m.def(
      "emitter_coupling_fo",
      [](const LidarSystem& system, double z, std::array<double, 2> position) {
        Interruptible release;
        return emitter_coupling_fo(system, z, {position[0], position[1]});
      },
      py::arg("system"), py::arg("z"), py::arg("position"));
}
