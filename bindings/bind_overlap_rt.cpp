// Ray-tracing overlap: options and result as classes; the GIL is released around the compute only.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <vector>

#include "arrays.hpp"
#include "interruptible.hpp"
#include "options.hpp"
#include "lidar_overlap/geometry/overlap_rt.hpp"
#include "lidar_overlap/geometry/receiver.hpp"

namespace py = pybind11;
using namespace lidar_overlap;

void bind_overlap_rt(py::module_& m) {
  bind_options(
      m, "RtOptions", "Options of overlap_rt and overlap_rt_batch.",
      option("tolerance", &RtOptions::tolerance,
             "Absolute error allowed on G at each range, in (0, 1)."),
      option("threads", &RtOptions::threads, "OpenMP threads across ranges; 0: all cores."),
      option("max_segments", &RtOptions::max_segments,
             "Cap on subdivisions per adaptive integral; reaching it clears `converged`."));

  py::class_<RtOverlap>(m, "RtOverlap", "Result of overlap_rt: one entry per range.")
      .def_property_readonly("overlap", [](const RtOverlap& r) { return to_array(r.overlap); })
      .def_property_readonly("error_estimate",
                             [](const RtOverlap& r) { return to_array(r.error_estimate); })
      .def_property_readonly("converged", [](const RtOverlap& r) { return to_array(r.converged); })
      .def_readonly("evaluations", &RtOverlap::evaluations,
                    "Scatterer couplings computed, all ranges.")
      .def_readonly("axisymmetric", &RtOverlap::axisymmetric,
                    "Beam and receiver share the telescope axis.");

  m.def(
      "overlap_rt",
      [](const LidarSystem& system, const std::vector<double>& ranges, const RtOptions& options) {
        Interruptible release;
        return overlap_rt(system, ranges, options);
      },
      py::arg("system"), py::arg("ranges"), py::arg("options") = RtOptions{});

  m.def(
      "overlap_rt_batch",
      [](const std::vector<LidarSystem>& systems, const std::vector<double>& ranges,
         const RtOptions& options) {
        Interruptible release;
        return overlap_rt_batch(systems, ranges, options);
      },
      py::arg("systems"), py::arg("ranges"), py::arg("options") = RtOptions{},
      "Entry i: G of systems[i] at ranges[i], bit for bit overlap_rt(systems[i], [ranges[i]], options).");

  m.def(
      "emitter_coupling_rt",
      [](const LidarSystem& system, double z, std::array<double, 2> position) {
        return emitter_coupling_rt(system, z, {position[0], position[1]});
      },
      py::arg("system"), py::arg("z"), py::arg("position"));

  m.def("optimal_focus_range", &optimal_focus_range, py::arg("focal_length"), py::arg("defocus"));
}
