// The turbulent atmosphere (Cn^2 profiles and their path integrals) and the turbulent FO overlap.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bind_field.hpp"
#include "interruptible.hpp"
#include "lidar_overlap/atmosphere/overlap_turbulent.hpp"
#include "lidar_overlap/atmosphere/phase_screen.hpp"
#include "lidar_overlap/atmosphere/turbulence.hpp"

namespace py = pybind11;
using namespace lidar_overlap;

void bind_turbulence(py::module_& m) {
  py::class_<Cn2Profile>(m, "Cn2Profile")
      .def_static("constant", &Cn2Profile::constant, py::arg("cn2"))
      .def_static("hufnagel_valley", &Cn2Profile::hufnagel_valley, py::arg("ground"), py::arg("wind"))
      // The callable is called from C++ while the GIL is held (these methods keep it).
      .def_static("custom", &Cn2Profile::custom, py::arg("cn2_of_height"))
      .def_readwrite("elevation", &Cn2Profile::elevation)
      .def_readwrite("altitude", &Cn2Profile::altitude)
      .def_readwrite("inner_scale", &Cn2Profile::inner_scale)
      .def_readwrite("outer_scale", &Cn2Profile::outer_scale)
      .def("validate", &Cn2Profile::validate)
      .def("cn2_at_range", &Cn2Profile::cn2_at_range, py::arg("range"))
      .def("cn2_at_height", &Cn2Profile::cn2_at_height, py::arg("height"))
      .def("fried_parameter_plane", &Cn2Profile::fried_parameter_plane, py::arg("wavelength"), py::arg("path_length"))
      .def("fried_parameter_spherical", &Cn2Profile::fried_parameter_spherical, py::arg("wavelength"),
           py::arg("path_length"))
      .def("rytov_variance", &Cn2Profile::rytov_variance, py::arg("wavelength"), py::arg("path_length"))
      .def("isoplanatic_angle", &Cn2Profile::isoplanatic_angle, py::arg("wavelength"), py::arg("path_length"))
      .def("beam_wander_variance", &Cn2Profile::beam_wander_variance, py::arg("waist_radius"), py::arg("wavelength"),
           py::arg("path_length"))
      .def("long_term_radius", &Cn2Profile::long_term_radius, py::arg("waist_radius"), py::arg("wavelength"),
           py::arg("path_length"))
      .def("short_term_radius", &Cn2Profile::short_term_radius, py::arg("waist_radius"), py::arg("wavelength"),
           py::arg("path_length"));

  m.def(
      "phase_screen",
      [](std::size_t n, double spacing, double r0, double outer_scale, double inner_scale, std::uint64_t seed,
         std::size_t index) {
        std::vector<double> s;
        {
          Interruptible release;
          s = PhaseScreenGenerator(n, spacing, r0, outer_scale, inner_scale).generate(seed, index);
        }
        return square_array(s, n);
      },
      py::arg("n"), py::arg("spacing"), py::arg("r0"), py::arg("outer_scale"), py::arg("inner_scale"), py::arg("seed"),
      py::arg("index"));

  m.def(
      "overlap_fo_turbulent",
      [](const LidarSystem& system, const std::vector<double>& ranges, const Cn2Profile& atmosphere,
         std::size_t realizations, std::size_t screens, std::uint64_t seed, std::size_t beam_grid, double beam_window,
         int threads) {
        TurbulentOverlap r;
        TurbulenceOptions o;
        o.realizations = realizations;
        o.screens = screens;
        o.seed = seed;
        o.beam_grid = beam_grid;
        o.beam_window = beam_window;
        o.threads = threads;
        {
          Interruptible release;  // a custom profile re-acquires it through pybind11's wrapper
          r = overlap_fo_turbulent(system, ranges, atmosphere, o);
        }
        py::array_t<double> g({r.overlap.size(), ranges.size()});
        for (std::size_t k = 0; k < r.overlap.size(); ++k)
          std::copy(r.overlap[k].begin(), r.overlap[k].end(), g.mutable_data() + k * ranges.size());
        py::dict out;
        out["overlap"] = g;
        out["wander_x"] = r.wander_x;
        out["wander_y"] = r.wander_y;
        out["radius_last"] = r.radius_last;
        return out;
      },
      py::arg("system"), py::arg("ranges"), py::arg("atmosphere"), py::arg("realizations"), py::arg("screens"),
      py::arg("seed"), py::arg("beam_grid"), py::arg("beam_window"), py::arg("threads"));
}
