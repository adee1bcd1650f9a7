// Alignment maps: axes as (name, values) pairs, the result's arrays shaped (axis sizes..., ranges).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "interruptible.hpp"
#include "lidar_overlap/geometry/alignment_map.hpp"

namespace py = pybind11;
using namespace lidar_overlap;

namespace {

template <class T>
py::array_t<T> shaped(const std::vector<T>& v, const std::vector<std::size_t>& shape) {
  py::array_t<T> out(shape);
  std::copy(v.begin(), v.end(), out.mutable_data());
  return out;
}

}  // namespace

void bind_alignment_map(py::module_& m) {
  m.attr("MAX_ALIGNMENT_POINTS") = kMaxAlignmentPoints;
  py::class_<AlignmentMap>(m, "AlignmentMap",
                           "Result of alignment_map: arrays shaped (axis sizes..., ranges).")
      .def_property_readonly("shape", [](const AlignmentMap& r) { return r.shape; })
      .def_property_readonly(
          "overlap", [](const AlignmentMap& r) { return shaped(r.values.overlap, r.shape); })
      .def_property_readonly(
          "error_estimate",
          [](const AlignmentMap& r) { return shaped(r.values.error_estimate, r.shape); })
      .def_property_readonly(
          "converged", [](const AlignmentMap& r) { return shaped(r.values.converged, r.shape); })
      .def_property_readonly(
          "evaluations", [](const AlignmentMap& r) { return r.values.evaluations; },
          "Scatterer couplings computed, all entries.")
      .def_property_readonly(
          "axisymmetric", [](const AlignmentMap& r) { return r.values.axisymmetric; },
          "Every grid point's system is axisymmetric.");

  m.def(
      "alignment_map",
      [](const LidarSystem& system,
         const std::vector<std::pair<std::string, std::vector<double>>>& axes,
         const std::vector<double>& ranges, const RtOptions& options) {
        std::vector<AlignmentAxis> native;
        for (const auto& [name, values] : axes)
          native.push_back({alignment_parameter_from_name(name), values});
        Interruptible release;
        return alignment_map(system, native, ranges, options);
      },
      py::arg("system"), py::arg("axes"), py::arg("ranges"), py::arg("options") = RtOptions{},
      "G over a grid of misalignments: axes are (name, values) pairs, values added to the system's own.");
  m.def(
      "alignment_parameters",
      [] {
        std::vector<std::string> names;
        for (int p = 0; p <= static_cast<int>(AlignmentParameter::defocus); ++p)
          names.push_back(alignment_parameter_name(static_cast<AlignmentParameter>(p)));
        return names;
      },
      "Names of the scalars alignment_map can vary.");
}
