// Propagation: the GIL is released around the FFT work; the report comes back as a PropagationReport.
#include <fftw3.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>

#include <stdexcept>
#include <string>
#include <vector>

#include "bind_field.hpp"
#include "interruptible.hpp"
#include "result_array.hpp"
#include "fourier/fft.hpp"
#include "fourier/fft_wisdom.hpp"
#include "lidar_overlap/fourier/grid_choice.hpp"
#include "lidar_overlap/fourier/propagate.hpp"

namespace py = pybind11;
using namespace lidar_overlap;

namespace {
PropagationMethod method_from(const std::string& name) {
  if (name == "auto") return PropagationMethod::automatic;
  if (name == "angular_spectrum") return PropagationMethod::angular_spectrum;
  if (name == "fresnel") return PropagationMethod::fresnel;
  if (name == "fraunhofer") return PropagationMethod::fraunhofer;
  throw std::invalid_argument(
      "method = '" + name +
      "' is invalid: expected 'auto', 'angular_spectrum', 'fresnel' or 'fraunhofer'");
}

const char* method_name(PropagationMethod m) {
  switch (m) {
    case PropagationMethod::angular_spectrum:
      return "angular_spectrum";
    case PropagationMethod::fresnel:
      return "fresnel";
    case PropagationMethod::fraunhofer:
      return "fraunhofer";
    default:
      return "auto";
  }
}
}  // namespace

void bind_propagate(py::module_& m) {
  py::class_<PropagationReport>(m, "PropagationReport",
                                "How a field was propagated, and its sampling checks.")
      .def_property_readonly(
          "method", [](const PropagationReport& r) { return method_name(r.method); },
          "The method actually used.")
      .def_readonly("critical_distance", &PropagationReport::critical_distance,
                    "m, n dx^2 / lambda.")
      .def_readonly(
          "band_limit_loss", &PropagationReport::band_limit_loss,
          "Angular spectrum: fraction of power outside the band-limited transfer function.")
      .def_readonly("input_edge_power", &PropagationReport::input_edge_power,
                    "Fraction of the input power in the outer n/16 of the window.")
      .def_readonly("output_edge_power", &PropagationReport::output_edge_power,
                    "The same for the output.")
      .def_readonly("scaled_output", &PropagationReport::scaled_output,
                    "Fresnel/Fraunhofer by chirp-z to a chosen spacing.")
      .def_readonly("chirp_phase_step", &PropagationReport::chirp_phase_step,
                    "rad, Fresnel: input chirp phase step at the field's edge.")
      .def_readonly("fresnel_phase_error", &PropagationReport::fresnel_phase_error,
                    "rad, Fresnel: phase neglected by the approximation (A3).")
      .def_readonly("fraunhofer_phase", &PropagationReport::fraunhofer_phase,
                    "rad, Fraunhofer: neglected input phase (A6).");

  m.def(
      "propagate",
      // grid_size: 0 keeps the field's grid, -1 lets choose_grid pick it, n > 0 zero-pads to n.
      [](const ComplexArray& values, double spacing, double wavelength, double distance,
         const std::string& method, double output_spacing, long grid_size) {
        if (values.ndim() != 2 || values.shape(0) != values.shape(1))
          throw std::invalid_argument("values: expected a square (n, n) complex array");
        PropagationMethod pm = method_from(method);
        std::size_t n = static_cast<std::size_t>(values.shape(0));
        Field padded;  // only when the grid changes: the caller's values zero-padded
        const Complex* in = values.data();
        if (grid_size != 0) {
          padded = field_from_array(values, spacing, wavelength);
          Interruptible release;
          if (grid_size == -1) {
            const GridChoice g = choose_grid(padded, distance, pm);
            pm = g.method;
            if (g.n != padded.n) padded = zero_pad(padded, g.n);
          } else if (static_cast<std::size_t>(grid_size) != padded.n) {
            padded = zero_pad(padded, static_cast<std::size_t>(grid_size));
          }
          n = padded.n;
          in = padded.values.data();
        }
        std::shared_ptr<const PropagationPlan> plan;
        {
          Interruptible release;  // a new geometry's transfer function: n^2 phasors
          plan = PropagationPlan::cached(n, spacing, wavelength, distance, pm, output_spacing);
        }
        // The passes read the caller's values (or the padded copy) and write the result's array: no copy.
        ComplexArray out = result_array(n);
        PropagationReport report;
        {
          Interruptible release;
          report = plan->execute(in, out.mutable_data());
        }
        return py::make_tuple(out, plan->output_spacing(), report);
      },
      py::arg("values"), py::arg("spacing"), py::arg("wavelength"), py::arg("distance"),
      py::arg("method"), py::arg("output_spacing"), py::arg("grid_size"));

  // The reference a propagation is timed against: the same copies in and out, a forward and a backward
  // FFT on the same cached plans, nothing else (unnormalised: the result is n^2 times the input).
  m.def(
      "fft2d_roundtrip",
      [](const ComplexArray& values) {
        Field f = field_from_array(values, 1.0, 1.0);
        {
          Interruptible release;
          fft2d(f.values, f.n, FftDirection::forward);
          fft2d(f.values, f.n, FftDirection::backward);
        }
        return array_from_field(f);
      },
      py::arg("values"));

  // The floor the benchmarks time the library's transforms against: FFTW's own 2-D plan of the same size,
  // planned with FFTW_MEASURE for `threads` threads (fastest on this machine now, but chosen by timing, so
  // its bits may differ between processes: a benchmark reference only). `transforms` = 1: one forward FFT;
  // 2: forward and backward. The same copies in and out as fft2d_roundtrip; plans made on first use.
  m.def(
      "_fftw_measured",
      [](const ComplexArray& values, int transforms, int threads) {
        if (transforms != 1 && transforms != 2)
          throw std::invalid_argument("transforms = " + std::to_string(transforms) +
                                      " is invalid: expected 1 or 2");
        if (threads < 1 || threads > 1024)
          throw std::invalid_argument("threads = " + std::to_string(threads) +
                                      " is invalid: expected 1 to 1024");
        Field f = field_from_array(values, 1.0, 1.0);
        static std::map<std::tuple<std::size_t, int, int>, fftw_plan> plans;
        auto plan = [&](int sign) {
          std::lock_guard<std::mutex> lock(fftw_planner_mutex());
          auto& p = plans[{f.n, threads, sign}];
          if (!p) {
            detail::init_fftw_threads();
            fftw_plan_with_nthreads(threads);
            ComplexBuffer scratch(f.n * f.n);
            auto* s = reinterpret_cast<fftw_complex*>(scratch.data());
            p = fftw_plan_dft_2d(static_cast<int>(f.n), static_cast<int>(f.n), s, s, sign,
                                 FFTW_MEASURE);
            fftw_plan_with_nthreads(1);
          }
          return p;
        };
        const fftw_plan forward = plan(FFTW_FORWARD),
                        backward = transforms == 2 ? plan(FFTW_BACKWARD) : nullptr;
        {
          Interruptible release;
          auto* p = reinterpret_cast<fftw_complex*>(f.values.data());
          fftw_execute_dft(forward, p, p);
          if (backward) fftw_execute_dft(backward, p, p);
        }
        return array_from_field(f);
      },
      py::arg("values"), py::arg("transforms"), py::arg("threads"));

  // The same floors without the copies, for timing the library's passes against the transforms alone: the
  // least time (s) of `transforms` (1: forward; 2: forward and backward) 2-D transforms on an n x n buffer
  // over `repeats`, with FFTW's measured plan for `threads` threads (`library` false; plans made on first
  // use and kept) or the library's deterministic transforms (true, on the threads fft_threads gives).
  m.def(
      "_fft_pair_seconds",
      [](std::size_t n, int repeats, bool library, int transforms, int threads) {
        if (n < 2 || n > 4096)
          throw std::invalid_argument("n = " + std::to_string(n) +
                                      " is invalid: expected 2 to 4096");
        if (repeats < 1 || repeats > 100000)
          throw std::invalid_argument("repeats = " + std::to_string(repeats) +
                                      " is invalid: expected 1 to 100000");
        if (transforms != 1 && transforms != 2)
          throw std::invalid_argument("transforms = " + std::to_string(transforms) +
                                      " is invalid: expected 1 or 2");
        if (threads < 1 || threads > 1024)
          throw std::invalid_argument("threads = " + std::to_string(threads) +
                                      " is invalid: expected 1 to 1024");
        ComplexBuffer data(n * n, Complex(1.0, 0.5));
        auto* p = reinterpret_cast<fftw_complex*>(data.data());
        fftw_plan forward = nullptr, backward = nullptr;
        if (!library) {
          static std::map<std::tuple<std::size_t, int, int>, fftw_plan> plans;
          std::lock_guard<std::mutex> lock(fftw_planner_mutex());
          auto plan = [&](int sign) {
            auto& q = plans[{n, threads, sign}];
            if (!q) {
              detail::init_fftw_threads();
              fftw_plan_with_nthreads(threads);
              ComplexBuffer scratch(n * n);
              auto* s = reinterpret_cast<fftw_complex*>(scratch.data());
              q = fftw_plan_dft_2d(int(n), int(n), s, s, sign, FFTW_MEASURE);
              fftw_plan_with_nthreads(1);
            }
            return q;
          };
          forward = plan(FFTW_FORWARD);
          backward = transforms == 2 ? plan(FFTW_BACKWARD) : nullptr;
        }
        double best = 1e300;
        {
          Interruptible release;
          for (int r = 0; r < repeats; ++r) {
            const auto t0 = std::chrono::steady_clock::now();
            if (library) {
              fft2d(data, n, FftDirection::forward);
              if (transforms == 2) fft2d(data, n, FftDirection::backward);
            } else {
              fftw_execute_dft(forward, p, p);
              if (backward) fftw_execute_dft(backward, p, p);
            }
            best = std::min(
                best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
            const double scale = 1.0 / std::pow(double(n), transforms);
            for (Complex& v : data) v *= scale;  // keep the values bounded
          }
        }
        return best;
      },
      py::arg("n"), py::arg("repeats"), py::arg("library"), py::arg("transforms") = 2,
      py::arg("threads") = 1);

  // The wisdom the library's 1-D block plans are made from (fourier/fft_wisdom.hpp): (FFTW's version string,
  // wisdom measured now for the given transform lengths), which scripts/make_fft_wisdom.py writes into the
  // source, and the same pair as shipped.
  m.def(
      "_measure_fft_wisdom",
      [](const std::vector<std::size_t>& lengths) {
        std::string wisdom;
        {
          Interruptible release;
          wisdom = detail::measure_fft_wisdom(lengths);
        }
        return std::make_pair(std::string(fftw_version), wisdom);
      },
      py::arg("lengths"));
  m.def("_merge_fft_wisdom", &detail::merge_fft_wisdom, py::arg("texts"));
  m.def(
      "_block_transform_seconds",
      [](std::size_t n, const std::string& wisdom, int repeats) {
        Interruptible release;
        return detail::block_transform_seconds(n, wisdom.c_str(), repeats);
      },
      py::arg("n"), py::arg("wisdom"), py::arg("repeats"));
  m.def("_shipped_fft_wisdom", [] {
    return std::make_pair(std::string(detail::shipped_fft_wisdom_fftw()),
                          std::string(detail::shipped_fft_wisdom()));
  });
}
