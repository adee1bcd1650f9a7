// Receiver aberrations: the Zernike/Seidel model and the two aberrated overlap paths, their options and results
// as classes. GIL released around the compute only.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <vector>

#include "arrays.hpp"
#include "bind_field.hpp"
#include "interruptible.hpp"
#include "options.hpp"
#include "lidar_overlap/pupil/aberrations.hpp"
#include "lidar_overlap/pupil/overlap_fo_aberrated.hpp"
#include "lidar_overlap/pupil/overlap_rt_aberrated.hpp"
#include "lidar_overlap/pupil/zernike.hpp"

namespace py = pybind11;
using namespace lidar_overlap;

namespace {
using Points = py::array_t<double, py::array::c_style | py::array::forcecast>;

// Applies f(Vec2) -> double to x, y arrays of one shape.
template <class F>
py::array_t<double> map_points(const Points& x, const Points& y, F f) {
  if (x.size() != y.size()) throw std::invalid_argument("x and y must have the same shape");
  py::array_t<double> out(std::vector<py::ssize_t>(x.shape(), x.shape() + x.ndim()));
  const double *px = x.data(), *py_ = y.data();
  double* o = out.mutable_data();
  for (py::ssize_t i = 0; i < x.size(); ++i) o[i] = f(Vec2{px[i], py_[i]});
  return out;
}
}  // namespace

void bind_aberrations(py::module_& m) {
  m.def(
      "noll_index",
      [](int j) {
        const ZernikeIndex z = noll_index(j);
        return std::array<int, 2>{z.n, z.m};
      },
      py::arg("j"));
  m.def(
      "zernike",
      [](int j, const Points& x, const Points& y) {
        noll_index(j);
        return map_points(x, y, [j](Vec2 p) { return zernike(j, p); });
      },
      py::arg("j"), py::arg("x"), py::arg("y"));

  py::class_<Aberrations>(m, "Aberrations")
      .def(py::init([](std::vector<double> zernike, double w040, double w131, double w222,
                       double w220, double w311, double field_radius) {
             Aberrations a{std::move(zernike), w040, w131, w222, w220, w311, field_radius};
             a.validate();
             return a;
           }),
           py::arg("zernike"), py::arg("w040"), py::arg("w131"), py::arg("w222"), py::arg("w220"),
           py::arg("w311"), py::arg("field_radius"))
      .def(
          "wavefront",
          [](const Aberrations& a, const Points& x, const Points& y, std::array<double, 2> field) {
            return map_points(x, y, [&](Vec2 p) { return a.wavefront(p, {field[0], field[1]}); });
          },
          py::arg("x"), py::arg("y"), py::arg("field"))
      .def(
          "gradient",
          [](const Aberrations& a, const Points& x, const Points& y, std::array<double, 2> field) {
            const Vec2 f{field[0], field[1]};
            return std::make_pair(map_points(x, y, [&](Vec2 p) { return a.gradient(p, f).x; }),
                                  map_points(x, y, [&](Vec2 p) { return a.gradient(p, f).y; }));
          },
          py::arg("x"), py::arg("y"), py::arg("field"))
      .def(
          "max_gradient",
          [](const Aberrations& a, std::array<double, 2> field) {
            return a.max_gradient({field[0], field[1]});
          },
          py::arg("field"))
      .def("field_dependent", &Aberrations::field_dependent)
      .def("none", &Aberrations::none);

  bind_options(
      m, "FoAberratedOptions", "Options of overlap_fo_aberrated.",
      option("max_grid", &FoAberratedOptions::max_grid,
             "Cap on the pupil transform's size per side."),
      option("tail_error", &FoAberratedOptions::tail_error,
             "Sets the alias period: the aliases' tails put this on G before they cancel."),
      option("threads", &FoAberratedOptions::threads,
             "OpenMP threads across ranges; 0: all cores."));
  bind_options(
      m, "RtAberratedOptions", "Options of overlap_rt_aberrated and emitter_coupling_rt_aberrated.",
      option("rings", &RtAberratedOptions::rings,
             "Rays per scatterer: rings equally spaced in rho^2 ..."),
      option("ring_rays", &RtAberratedOptions::ring_rays, "... times rays per ring."),
      option("tolerance", &RtAberratedOptions::tolerance, "Absolute, on G, for the beam integral."),
      option(
          "directions", &RtAberratedOptions::directions,
          "Cap on the directions of the beam integral when the scene is not rotationally symmetric."),
      option("threads", &RtAberratedOptions::threads,
             "OpenMP threads across ranges; 0: all cores."),
      option("max_segments", &RtAberratedOptions::max_segments,
             "Cap on subdivisions per adaptive integral; reaching it clears `converged`."));

  py::class_<FoAberratedOverlap>(m, "FoAberratedOverlap",
                                 "Result of overlap_fo_aberrated: one entry per range.")
      .def_property_readonly("overlap",
                             [](const FoAberratedOverlap& r) { return to_array(r.overlap); })
      .def_property_readonly(
          "grid", [](const FoAberratedOverlap& r) { return to_array(r.grid); },
          "Transform size used at each range.");
  py::class_<RtAberratedOverlap>(m, "RtAberratedOverlap",
                                 "Result of overlap_rt_aberrated: one entry per range.")
      .def_property_readonly("overlap",
                             [](const RtAberratedOverlap& r) { return to_array(r.overlap); })
      .def_property_readonly("error_estimate",
                             [](const RtAberratedOverlap& r) { return to_array(r.error_estimate); })
      .def_property_readonly("converged",
                             [](const RtAberratedOverlap& r) { return to_array(r.converged); })
      .def_readonly("rotationally_symmetric", &RtAberratedOverlap::rotationally_symmetric,
                    "One radial integral per range.")
      .def_readonly("pupil_form", &RtAberratedOverlap::pupil_form,
                    "Computed as one pupil integral per range.");

  m.def(
      "overlap_fo_aberrated",
      [](const LidarSystem& system, const Aberrations& aberrations,
         const std::vector<double>& ranges, const FoAberratedOptions& options) {
        Interruptible release;
        return overlap_fo_aberrated(system, aberrations, ranges, options);
      },
      py::arg("system"), py::arg("aberrations"), py::arg("ranges"),
      py::arg("options") = FoAberratedOptions{});

  m.def(
      "overlap_rt_aberrated",
      [](const LidarSystem& system, const Aberrations& aberrations,
         const std::vector<double>& ranges, const RtAberratedOptions& options) {
        Interruptible release;
        return overlap_rt_aberrated(system, aberrations, ranges, options);
      },
      py::arg("system"), py::arg("aberrations"), py::arg("ranges"),
      py::arg("options") = RtAberratedOptions{});

  m.def(
      "emitter_coupling_rt_aberrated",
      [](const LidarSystem& system, const Aberrations& aberrations, double z,
         std::array<double, 2> position, const RtAberratedOptions& options) {
        return emitter_coupling_rt_aberrated(system, aberrations, z, {position[0], position[1]},
                                             options);
      },
      py::arg("system"), py::arg("aberrations"), py::arg("z"), py::arg("position"),
      py::arg("options") = point_coupling_options());

  m.def(
      "point_image",
      [](const LidarSystem& system, const Aberrations& aberrations, double z, std::size_t n,
         double spacing) {
        Field f;
        {
          Interruptible release;
          f = point_image(system, aberrations, z, n, spacing);
        }
        return array_from_field(f);
      },
      py::arg("system"), py::arg("aberrations"), py::arg("z"), py::arg("n"), py::arg("spacing"));
}
