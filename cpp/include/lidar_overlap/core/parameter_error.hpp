// The error every argument check throws: a std::invalid_argument (Python: a ValueError) whose message
// names the parameter, the value received and the valid range, and which carries the three as data,
// so that a caller can tell which parameter was refused without reading the message.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace lidar_overlap {

class ParameterError : public std::invalid_argument {
 public:
  ParameterError(const std::string& message, std::string parameter, double value,
                 std::string expected)
      : std::invalid_argument(message),
        parameter_(std::move(parameter)),
        value_(value),
        expected_(std::move(expected)) {}

  // The parameter as the caller names it: "beam.offset[0]", "ranges[3]", "beam_grid".
  const std::string& parameter() const noexcept { return parameter_; }
  // The value refused (a count as a double; NaN where the value is no number).
  double value() const noexcept { return value_; }
  // What was expected, as the message says it after "expected".
  const std::string& expected() const noexcept { return expected_; }

 private:
  std::string parameter_;
  double value_;
  std::string expected_;
};

}  // namespace lidar_overlap
