// Limits, errors and cancellation: the memory budget and thread cap every entry point enforces,
// lidar_overlap::ParameterError raised as _core.ParameterError (a ValueError carrying the parameter, value and
// expected range as attributes), and lidar_overlap::Cancelled raised as the pending KeyboardInterrupt.
#include <pybind11/pybind11.h>

#include <exception>

#include "lidar_overlap/core/cancel.hpp"
#include "lidar_overlap/core/limits.hpp"
#include "lidar_overlap/core/parameter_error.hpp"
#include "interruptible.hpp"

namespace py = pybind11;
using namespace lidar_overlap;

void bind_limits(py::module_& m) {
  m.def("max_memory", &max_memory, "Bytes one call may allocate for its grids and tables.");
  m.def("set_max_memory", &set_max_memory, py::arg("bytes"),
        "Set that budget in bytes (0 restores the default, a quarter of the physical memory).");
  m.def("max_threads", &max_threads, "The largest `threads` option accepted.");
  m.def(
      "_set_interrupt_requested", [](bool on) { interrupt_requested().store(on); }, py::arg("on"),
      "Ask every running core call, in any thread, to stop (the package's SIGINT handler).");
  m.attr("MIN_LENGTH") = kMinLength;
  m.attr("MAX_LENGTH") = kMaxLength;
  m.attr("MAX_ANGLE") = kMaxAngle;
  m.attr("MAX_GRID_SIDE") = kMaxGridSide;
  m.attr("MIN_TOLERANCE") = kMinTolerance;
  // Made once (the module lives as long as the interpreter); the package's _checks raises it too.
  static py::exception<ParameterError> parameter_error(m, "ParameterError", PyExc_ValueError);
  parameter_error.attr("__doc__") =
      "A ValueError naming a parameter: .parameter (its name as the caller spells it, e.g. "
      "'beam.offset[0]' or 'ranges[3]'), .value (the value refused) and .expected (the valid range, "
      "in words).";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ParameterError& e) {
      py::object error = py::handle(parameter_error.ptr())(e.what());
      error.attr("parameter") = e.parameter();
      error.attr("value") = e.value();
      error.attr("expected") = e.expected();
      PyErr_SetObject(parameter_error.ptr(), error.ptr());
    } catch (const Cancelled& e) {
      if (!PyErr_Occurred()) PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    }
  });
}
