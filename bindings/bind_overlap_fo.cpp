// Fourier-optics overlap: the GIL is released around the compute only.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <vector>

#include "bind_field.hpp"
#include "interruptible.hpp"
#include "lidar_overlap/fourier/overlap_fo.hpp"
#include "lidar_overlap/fourier/overlap_fo_radial.hpp"

namespace py = pybind11;
using namespace lidar_overlap;

namespace {
py::dict to_dict(const FoOverlap& r) {
  py::list reports;
  for (const PropagationReport& p : r.beam_reports) reports.append(report_dict(p));
  py::dict out;
  out["overlap"] = py::array_t<double>(r.overlap.size(), r.overlap.data());
  out["spectrum_grid"] = r.spectrum_grid;
  out["beam_reports"] = reports;
  return out;
}
}  // namespace

void bind_overlap_fo(py::module_& m) {
  m.def(
      "overlap_fo",
      [](const LidarSystem& system, const std::vector<double>& ranges, std::size_t beam_grid, double beam_window,
         std::size_t max_spectrum_grid, int threads) {
        FoOverlap r;
        {
          Interruptible release;
          r = overlap_fo(system, ranges, FoOptions{beam_grid, beam_window, max_spectrum_grid, threads});
        }
        return to_dict(r);
      },
      py::arg("system"), py::arg("ranges"), py::arg("beam_grid"), py::arg("beam_window"),
      py::arg("max_spectrum_grid"), py::arg("threads"));

  // Any transmitted field (flat-top, annular, vortex, ...): the field's own grid replaces beam_grid.
  m.def(
      "overlap_fo_field",
      [](const LidarSystem& system, const std::vector<double>& ranges, const ComplexArray& values, double spacing,
         double wavelength, std::size_t max_spectrum_grid, int threads) {
        const Field transmitted = field_from_array(values, spacing, wavelength);
        FoOverlap r;
        {
          Interruptible release;
          FoOptions options;
          options.max_spectrum_grid = max_spectrum_grid;
          options.threads = threads;
          r = overlap_fo(system, ranges, transmitted, options);
        }
        return to_dict(r);
      },
      py::arg("system"), py::arg("ranges"), py::arg("values"), py::arg("spacing"), py::arg("wavelength"),
      py::arg("max_spectrum_grid"), py::arg("threads"));

  m.def(
      "overlap_fo_radial",
      [](const LidarSystem& system, const std::vector<double>& ranges, double periods_per_panel, int threads) {
        RadialFoOverlap r;
        {
          Interruptible release;
          r = overlap_fo_radial(system, ranges, RadialFoOptions{periods_per_panel, threads});
        }
        py::dict out;
        out["overlap"] = py::array_t<double>(r.overlap.size(), r.overlap.data());
        out["evaluations"] = r.evaluations;
        return out;
      },
      py::arg("system"), py::arg("ranges"), py::arg("periods_per_panel"), py::arg("threads"));

  m.def(
      "emitter_coupling_fo",
      [](const LidarSystem& system, double z, std::array<double, 2> position) {
        Interruptible release;
        return emitter_coupling_fo(system, z, {position[0], position[1]});
      },
      py::arg("system"), py::arg("z"), py::arg("position"));
}
