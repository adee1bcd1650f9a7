// The lidar_overlap._core extension: one bind_<concept> function per header group.
#include <pybind11/pybind11.h>

#include "lidar_overlap/version.hpp"

namespace py = pybind11;

void bind_limits(py::module_& m);
void bind_system(py::module_& m);
void bind_overlap_rt(py::module_& m);
void bind_aperture_mask(py::module_& m);
void bind_alignment_map(py::module_& m);
void bind_field(py::module_& m);
void bind_propagate(py::module_& m);
void bind_overlap_fo(py::module_& m);
void bind_flat_top(py::module_& m);
void bind_turbulence(py::module_& m);
void bind_aberrations(py::module_& m);

PYBIND11_MODULE(_core, m) {
  m.doc() = "C++ core of lidar_overlap (SI units throughout).";
  m.attr("__version__") = lidar_overlap::kVersion;
  bind_limits(m);
  bind_system(m);
  bind_overlap_rt(m);
  bind_alignment_map(m);
  bind_field(m);
  bind_propagate(m);
  bind_overlap_fo(m);
  bind_flat_top(m);
  bind_turbulence(m);
  bind_aberrations(m);
  bind_aperture_mask(m);  // after bind_aberrations: its FO entry defaults to FoAberratedOptions
}
