#include "lidar_overlap/checks.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace lidar_overlap::checks {

void fail(const std::string& parameter, double value, const std::string& valid_range) {
  std::ostringstream msg;
  msg.precision(17);
  msg << parameter << " = " << value << " is invalid: expected " << valid_range;
  throw std::invalid_argument(msg.str());
}

void finite(const std::string& parameter, double value) {
  if (!std::isfinite(value)) fail(parameter, value, "a finite number");
}

void finite(const std::string& parameter, Vec2 value) {
  finite(parameter + "[0]", value.x);
  finite(parameter + "[1]", value.y);
}

void positive(const std::string& parameter, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) fail(parameter, value, "a finite value > 0");
}

void non_negative(const std::string& parameter, double value) {
  if (!(value >= 0.0) || !std::isfinite(value)) fail(parameter, value, "a finite value >= 0");
}

void in_open_unit(const std::string& parameter, double value) {
  if (!(value > 0.0 && value < 1.0)) fail(parameter, value, "a value in (0, 1)");
}

}  // namespace lidar_overlap::checks
