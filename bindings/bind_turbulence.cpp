// The turbulent atmosphere (Cn^2 profiles and their path integrals) and the turbulent FO overlap, its options
// and result as classes.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bind_field.hpp"
#include "interruptible.hpp"
#include "options.hpp"
#include "lidar_overlap/atmosphere/overlap_turbulent.hpp"
#include "lidar_overlap/atmosphere/phase_screen.hpp"
#include "lidar_overlap/atmosphere/turbulence.hpp"
#include "lidar_overlap/atmosphere/turbulent_grid.hpp"

namespace py = pybind11;
using namespace lidar_overlap;

// TurbulencePaths as the strings "transmit" and "both" (an unknown string is refused by name).
namespace pybind11::detail {
template <>
struct type_caster<TurbulencePaths> {
  PYBIND11_TYPE_CASTER(TurbulencePaths, const_name("str"));
  bool load(handle src, bool) {
    if (!isinstance<str>(src)) return false;
    const std::string s = src.cast<std::string>();
    if (s != "transmit" && s != "both")
      throw std::invalid_argument("paths = '" + s + "' is invalid: expected 'transmit' or 'both'");
    value = s == "both" ? TurbulencePaths::both : TurbulencePaths::transmit;
    return true;
  }
  static handle cast(TurbulencePaths v, return_value_policy, handle) {
    return str(v == TurbulencePaths::both ? "both" : "transmit").release();
  }
};
}  // namespace pybind11::detail

void bind_turbulence(py::module_& m) {
  py::class_<Cn2Profile>(m, "Cn2Profile")
      .def_static("constant", &Cn2Profile::constant, py::arg("cn2"))
      .def_static("hufnagel_valley", &Cn2Profile::hufnagel_valley, py::arg("ground"),
                  py::arg("wind"))
      // The callable is called from C++ while the GIL is held (these methods keep it).
      .def_static("custom", &Cn2Profile::custom, py::arg("cn2_of_height"))
      .def_readwrite("elevation", &Cn2Profile::elevation)
      .def_readwrite("altitude", &Cn2Profile::altitude)
      .def_readwrite("inner_scale", &Cn2Profile::inner_scale)
      .def_readwrite("outer_scale", &Cn2Profile::outer_scale)
      .def("validate", &Cn2Profile::validate)
      .def("cn2_at_range", &Cn2Profile::cn2_at_range, py::arg("range"))
      .def("cn2_at_height", &Cn2Profile::cn2_at_height, py::arg("height"))
      .def("fried_parameter_plane", &Cn2Profile::fried_parameter_plane, py::arg("wavelength"),
           py::arg("path_length"))
      .def("fried_parameter_spherical", &Cn2Profile::fried_parameter_spherical,
           py::arg("wavelength"), py::arg("path_length"))
      .def("rytov_variance", &Cn2Profile::rytov_variance, py::arg("wavelength"),
           py::arg("path_length"))
      .def("isoplanatic_angle", &Cn2Profile::isoplanatic_angle, py::arg("wavelength"),
           py::arg("path_length"))
      .def("beam_wander_variance", &Cn2Profile::beam_wander_variance, py::arg("waist_radius"),
           py::arg("wavelength"), py::arg("path_length"))
      .def("long_term_radius", &Cn2Profile::long_term_radius, py::arg("waist_radius"),
           py::arg("wavelength"), py::arg("path_length"))
      .def("short_term_radius", &Cn2Profile::short_term_radius, py::arg("waist_radius"),
           py::arg("wavelength"), py::arg("path_length"));

  m.def(
      "phase_screen",
      [](std::size_t n, double spacing, double r0, double outer_scale, double inner_scale,
         std::uint64_t seed, std::size_t index) {
        std::vector<double> s;
        {
          Interruptible release;
          s = PhaseScreenGenerator(n, spacing, r0, outer_scale, inner_scale).generate(seed, index);
        }
        return square_array(s, n);
      },
      py::arg("n"), py::arg("spacing"), py::arg("r0"), py::arg("outer_scale"),
      py::arg("inner_scale"), py::arg("seed"), py::arg("index"));

  bind_options(
      m, "TurbulenceOptions", "Options of overlap_fo_turbulent.",
      option(
          "realizations", &TurbulenceOptions::realizations,
          "Random draws of the atmosphere computed: first_realization, first_realization + 1, ..."),
      option("first_realization", &TurbulenceOptions::first_realization,
             "Index of the first draw in the run of seed: its rows equal those of the whole run."),
      option("screens", &TurbulenceOptions::screens, "Phase screens over [0, last range]."),
      option("seed", &TurbulenceOptions::seed,
             "Same seed, same screens, whatever the thread count."),
      option("beam_grid", &TurbulenceOptions::beam_grid,
             "Samples per side of the propagated field."),
      option("beam_window", &TurbulenceOptions::beam_window,
             "Window in long-term radii (plus 8 rms wander) at every plane."),
      option("max_spectrum_grid", &TurbulenceOptions::max_spectrum_grid,
             "Cap on the zero-padded beam spectrum."),
      option("threads", &TurbulenceOptions::threads,
             "OpenMP threads across realisations; 0: all cores."),
      option(
          "paths", &TurbulenceOptions::paths,
          "transmit: the return path unperturbed; both: the return path through the same screens."),
      option("receiver_fields", &TurbulenceOptions::receiver_fields,
             "paths = both: random-phase fields standing for the incoherent detector."));

  py::class_<TurbulentOverlap>(m, "TurbulentOverlap", "Result of overlap_fo_turbulent.")
      .def_property_readonly(
          "overlap", [](const TurbulentOverlap& r) { return to_array(r.overlap); },
          "G, realisations x ranges.")
      .def_property_readonly(
          "wander_x", [](const TurbulentOverlap& r) { return to_array(r.wander_x); },
          "m, beam centroid at the last range, per realisation.")
      .def_property_readonly("wander_y",
                             [](const TurbulentOverlap& r) { return to_array(r.wander_y); })
      .def_property_readonly(
          "radius_last", [](const TurbulentOverlap& r) { return to_array(r.radius_last); },
          "m, second-moment radius at the last range, per realisation.")
      .def_property_readonly(
          "uncorrelated", [](const TurbulentOverlap& r) { return to_array(r.uncorrelated); },
          "paths = both: G of each draw's beam with an independent draw's receiver (empty for transmit).")
      .def_property_readonly(
          "receiver_error", [](const TurbulentOverlap& r) { return to_array(r.receiver_error); },
          "paths = both: standard error of each draw's G from its random-phase receiver fields.")
      .def_property_readonly(
          "receiver_x", [](const TurbulentOverlap& r) { return to_array(r.receiver_x); },
          "paths = both: m, centroid of the receiver's sensitivity at the last range, per realisation.")
      .def_property_readonly("receiver_y",
                             [](const TurbulentOverlap& r) { return to_array(r.receiver_y); })
      .def_property_readonly(
          "screen_range", [](const TurbulentOverlap& r) { return to_array(r.screen_range); }, "m")
      .def_property_readonly(
          "screen_spacing", [](const TurbulentOverlap& r) { return to_array(r.screen_spacing); },
          "m")
      .def_property_readonly(
          "screen_r0", [](const TurbulentOverlap& r) { return to_array(r.screen_r0); }, "m");

  m.def(
      "overlap_fo_turbulent",
      [](const LidarSystem& system, const std::vector<double>& ranges, const Cn2Profile& atmosphere,
         const TurbulenceOptions& options) {
        Interruptible release;  // a custom profile re-acquires it through pybind11's wrapper
        return overlap_fo_turbulent(system, ranges, atmosphere, options);
      },
      py::arg("system"), py::arg("ranges"), py::arg("atmosphere"),
      py::arg("options") = TurbulenceOptions{});

  // The grids overlap_fo_turbulent would use (atmosphere/turbulent_grid.hpp): cheap, and the GIL is kept for
  // a custom profile's callable.
  py::class_<TurbulentGrid>(m, "TurbulentGrid", "The grids of overlap_fo_turbulent for a scene.")
      .def_property_readonly(
          "plane_range", [](const TurbulentGrid& g) { return to_array(g.plane_range); },
          "m, the planes in propagation order (screens and ranges).")
      .def_property_readonly(
          "window", [](const TurbulentGrid& g) { return to_array(g.window); },
          "m, each plane's grid side (spacing x beam_grid).")
      .def_readonly("pupil_window", &TurbulentGrid::pupil_window,
                    "m, the transmitter plane's grid side.")
      .def_readonly("min_beam_grid", &TurbulentGrid::min_beam_grid,
                    "The least beam_grid the call accepts.");
  m.def("turbulent_grid", &turbulent_grid, py::arg("system"), py::arg("ranges"),
        py::arg("atmosphere"), py::arg("options") = TurbulenceOptions{});
  m.def("turbulent_both_bytes", &turbulent_both_bytes, py::arg("beam_grid"), py::arg("screens"),
        py::arg("receiver_fields"), py::arg("threads"));
}
