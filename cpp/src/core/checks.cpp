#include "core/checks.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "lidar_overlap/core/limits.hpp"
#include "lidar_overlap/core/parameter_error.hpp"

namespace lidar_overlap::checks {

void fail(const std::string& parameter, double value, const std::string& valid_range) {
  std::ostringstream msg;
  msg.precision(17);
  msg << parameter << " = " << value << " is invalid: expected " << valid_range;
  throw ParameterError(msg.str(), parameter, value, valid_range);
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

void tolerance(const std::string& parameter, double value) {
  if (!(value >= kMinTolerance && value < 1.0))
    fail(parameter, value,
         "a value in [" + number(kMinTolerance) +
             ", 1) (an absolute error on G; double precision resolves none smaller)");
}

std::string number(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

namespace {
std::string gib(double bytes) {
  const double mib = bytes / double(std::size_t{1} << 20);
  return mib < 1024.0 ? number(mib) + " MiB" : number(mib / 1024.0) + " GiB";
}
}  // namespace

void length(const std::string& parameter, double value) {
  if (!(value >= kMinLength && value <= kMaxLength))
    fail(parameter, value,
         "a finite value > 0: a length from " + number(kMinLength) + " m to " + number(kMaxLength) +
             " m");
}

void coordinate(const std::string& parameter, double value) {
  if (!(std::abs(value) <= kMaxLength))
    fail(parameter, value, "a finite value within +-" + number(kMaxLength) + " m");
}

void coordinate(const std::string& parameter, Vec2 value) {
  coordinate(parameter + "[0]", value.x);
  coordinate(parameter + "[1]", value.y);
}

void angle(const std::string& parameter, double value) {
  if (!(std::abs(value) <= kMaxAngle))
    fail(parameter, value, "an angle within +-" + number(kMaxAngle) + " rad (the paraxial model)");
}

void angle(const std::string& parameter, Vec2 value) {
  angle(parameter + "[0]", value.x);
  angle(parameter + "[1]", value.y);
}

std::size_t saturate(double x) {
  constexpr double kCap = 4611686018427387904.0;  // 2^62
  if (x >= 0.0 && x < kCap) return static_cast<std::size_t>(x);
  return x < 0.0 ? 0 : static_cast<std::size_t>(kCap);
}

std::size_t count_from(double estimate, std::size_t limit, const std::string& parameter,
                       double value, const std::string& why) {
  if (!(estimate >= 0.0 && estimate <= static_cast<double>(limit))) {
    std::ostringstream msg;
    msg.precision(17);
    msg << parameter << " = " << value << " asks for " << number(estimate) << " " << why
        << " (at most " << limit << ")";
    throw ParameterError(msg.str(), parameter, value,
                         "at most " + std::to_string(limit) + " " + why);
  }
  return static_cast<std::size_t>(estimate);
}

void grid(const std::string& parameter, std::size_t n, std::size_t bytes_per_point,
          std::size_t copies) {
  if (n > kMaxGridSide)
    fail(parameter, static_cast<double>(n),
         "at most " + std::to_string(kMaxGridSide) + " samples per side");
  const double bytes = double(n) * double(n) * double(bytes_per_point) * double(copies);
  memory(parameter, static_cast<double>(n), bytes,
         "use a smaller grid, or raise the budget with set_max_memory");
}

void memory(const std::string& parameter, double value, double bytes, const std::string& fix) {
  if (!(bytes <= static_cast<double>(max_memory()))) {
    std::ostringstream msg;
    msg.precision(17);
    const std::string budget = gib(static_cast<double>(max_memory()));
    msg << parameter << " = " << value << " needs " << gib(bytes)
        << " of memory, more than the budget of " << budget << " (max_memory): " << fix;
    throw ParameterError(msg.str(), parameter, value,
                         "at most " + budget + " of memory (max_memory)");
  }
}

void overlap_values(std::vector<double>& overlap, const std::vector<double>& ranges, double slack,
                    const std::string& method,
                    const std::function<std::string(std::size_t)>& cause) {
  overlap_values(overlap, ranges, std::vector<double>(overlap.size(), slack), method, cause);
}

void overlap_values(std::vector<double>& overlap, const std::vector<double>& ranges,
                    const std::vector<double>& slacks, const std::string& method,
                    const std::function<std::string(std::size_t)>& cause) {
  for (std::size_t i = 0; i < overlap.size(); ++i) {
    const double g = overlap[i], slack = slacks[i];
    if (g >= -slack && g <= 1.0 + slack) {
      overlap[i] = std::clamp(g, 0.0, 1.0);
      continue;
    }
    std::ostringstream msg;
    msg.precision(17);
    msg << method << ": G = " << g << " at ranges[" << i
        << "] = " << (i < ranges.size() ? ranges[i] : NAN)
        << " m is outside [0, 1] by more than the method's accuracy " << slack << ": "
        << (cause ? cause(i) : std::string())
        << (cause && !cause(i).empty()
                ? ""
                : "the inputs reach scales where the computation loses its precision; "
                  "check the system's scales");
    throw std::domain_error(msg.str());
  }
}

}  // namespace lidar_overlap::checks
