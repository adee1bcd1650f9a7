// Argument checks shared by every public entry point. Each throws std::invalid_argument whose
// message names the parameter, the value received and the valid range (Python sees ValueError).
#pragma once

#include <string>

#include "lidar_overlap/vec2.hpp"

namespace lidar_overlap::checks {

[[noreturn]] void fail(const std::string& parameter, double value, const std::string& valid_range);

void finite(const std::string& parameter, double value);
void finite(const std::string& parameter, Vec2 value);
void positive(const std::string& parameter, double value);        // 0 < value < inf
void non_negative(const std::string& parameter, double value);    // 0 <= value < inf
void in_open_unit(const std::string& parameter, double value);    // 0 < value < 1

}  // namespace lidar_overlap::checks
