// Ray-tracing overlap: the GIL is released around the compute only.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <vector>

#include "interruptible.hpp"
#include "lidar_overlap/geometry/overlap_rt.hpp"
#include "lidar_overlap/geometry/receiver.hpp"

namespace py = pybind11;
using namespace lidar_overlap;

void bind_overlap_rt(py::module_& m) {
  m.def(
      "overlap_rt",
      [](const LidarSystem& system, const std::vector<double>& ranges, double tolerance, int threads,
         std::size_t max_segments) {
        RtOverlap r;
        {
          Interruptible release;
          r = overlap_rt(system, ranges, RtOptions{tolerance, threads, max_segments});
        }
        py::dict out;
        out["overlap"] = py::array_t<double>(r.overlap.size(), r.overlap.data());
        out["error_estimate"] = py::array_t<double>(r.error_estimate.size(), r.error_estimate.data());
        out["converged"] = std::vector<bool>(r.converged.begin(), r.converged.end());
        out["evaluations"] = r.evaluations;
        out["axisymmetric"] = r.axisymmetric;
        return out;
      },
      py::arg("system"), py::arg("ranges"), py::arg("tolerance"), py::arg("threads"),
      py::arg("max_segments"));

  m.def(
      "emitter_coupling_rt",
      [](const LidarSystem& system, double z, std::array<double, 2> position) {
        return emitter_coupling_rt(system, z, {position[0], position[1]});
      },
      py::arg("system"), py::arg("z"), py::arg("position"));

  m.def("optimal_focus_range", &optimal_focus_range, py::arg("focal_length"), py::arg("defocus"));
}
