// Receiver aberrations: the Zernike/Seidel model and the two aberrated overlap paths. GIL released around
// the compute only.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <vector>

#include "bind_field.hpp"
#include "interruptible.hpp"
#include "lidar_overlap/aberrations/aberrations.hpp"
#include "lidar_overlap/aberrations/overlap_fo_aberrated.hpp"
#include "lidar_overlap/aberrations/overlap_rt_aberrated.hpp"
#include "lidar_overlap/aberrations/zernike.hpp"

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
  m.def("noll_index", [](int j) { const ZernikeIndex z = noll_index(j); return std::array<int, 2>{z.n, z.m}; },
        py::arg("j"));
  m.def("zernike", [](int j, const Points& x, const Points& y) {
    noll_index(j);
    return map_points(x, y, [j](Vec2 p) { return zernike(j, p); });
  }, py::arg("j"), py::arg("x"), py::arg("y"));

  py::class_<Aberrations>(m, "Aberrations")
      .def(py::init([](std::vector<double> zernike, double w040, double w131, double w222, double w220, double w311,
                       double field_radius) {
             Aberrations a{std::move(zernike), w040, w131, w222, w220, w311, field_radius};
             a.validate();
             return a;
           }),
           py::arg("zernike"), py::arg("w040"), py::arg("w131"), py::arg("w222"), py::arg("w220"), py::arg("w311"),
           py::arg("field_radius"))
      .def("wavefront", [](const Aberrations& a, const Points& x, const Points& y, std::array<double, 2> field) {
        return map_points(x, y, [&](Vec2 p) { return a.wavefront(p, {field[0], field[1]}); });
      }, py::arg("x"), py::arg("y"), py::arg("field"))
      .def("gradient", [](const Aberrations& a, const Points& x, const Points& y, std::array<double, 2> field) {
        const Vec2 f{field[0], field[1]};
        return std::make_pair(map_points(x, y, [&](Vec2 p) { return a.gradient(p, f).x; }),
                              map_points(x, y, [&](Vec2 p) { return a.gradient(p, f).y; }));
      }, py::arg("x"), py::arg("y"), py::arg("field"))
      .def("max_gradient", [](const Aberrations& a, std::array<double, 2> field) {
        return a.max_gradient({field[0], field[1]});
      }, py::arg("field"))
      .def("field_dependent", &Aberrations::field_dependent)
      .def("none", &Aberrations::none);

  m.def("overlap_fo_aberrated", [](const LidarSystem& system, const Aberrations& aberrations,
                                   const std::vector<double>& ranges, std::size_t max_grid, double tail_error,
                                   int threads) {
    FoAberratedOverlap r;
    {
      Interruptible release;
      r = overlap_fo_aberrated(system, aberrations, ranges, FoAberratedOptions{max_grid, tail_error, threads});
    }
    py::dict out;
    out["overlap"] = py::array_t<double>(r.overlap.size(), r.overlap.data());
    out["grid"] = r.grid;
    return out;
  }, py::arg("system"), py::arg("aberrations"), py::arg("ranges"), py::arg("max_grid"), py::arg("tail_error"),
     py::arg("threads"));

  m.def("overlap_rt_aberrated", [](const LidarSystem& system, const Aberrations& aberrations,
                                   const std::vector<double>& ranges, std::size_t rings, std::size_t ring_rays,
                                   double tolerance, std::size_t directions, int threads, std::size_t max_segments) {
    RtAberratedOverlap r;
    {
      Interruptible release;
      r = overlap_rt_aberrated(system, aberrations, ranges,
                               RtAberratedOptions{rings, ring_rays, tolerance, directions, threads, max_segments});
    }
    py::dict out;
    out["overlap"] = py::array_t<double>(r.overlap.size(), r.overlap.data());
    out["error_estimate"] = py::array_t<double>(r.error_estimate.size(), r.error_estimate.data());
    out["converged"] = std::vector<bool>(r.converged.begin(), r.converged.end());
    out["rotationally_symmetric"] = r.rotationally_symmetric;
    return out;
  }, py::arg("system"), py::arg("aberrations"), py::arg("ranges"), py::arg("rings"), py::arg("ring_rays"),
     py::arg("tolerance"), py::arg("directions"), py::arg("threads"), py::arg("max_segments"));

  m.def("emitter_coupling_rt_aberrated", [](const LidarSystem& system, const Aberrations& aberrations, double z,
                                            std::array<double, 2> position, std::size_t rings, std::size_t ring_rays) {
    RtAberratedOptions o;
    o.rings = rings;
    o.ring_rays = ring_rays;
    return emitter_coupling_rt_aberrated(system, aberrations, z, {position[0], position[1]}, o);
  }, py::arg("system"), py::arg("aberrations"), py::arg("z"), py::arg("position"), py::arg("rings"),
     py::arg("ring_rays"));

  m.def("point_image", [](const LidarSystem& system, const Aberrations& aberrations, double z, std::size_t n,
                          double spacing) {
    Field f;
    {
      Interruptible release;
      f = point_image(system, aberrations, z, n, spacing);
    }
    return array_from_field(f);
  }, py::arg("system"), py::arg("aberrations"), py::arg("z"), py::arg("n"), py::arg("spacing"));
}
