// Argument checks shared by every public entry point. Each throws ParameterError (a std::invalid_argument,
// lidar_overlap/core/parameter_error.hpp) whose message names the parameter, the value received and the valid
// range, and which carries them as data (Python sees lidar_overlap.ParameterError, a ValueError).
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "lidar_overlap/core/parameter_error.hpp"
#include "lidar_overlap/core/vec2.hpp"

namespace lidar_overlap::checks {

// A number for messages: 6 significant digits, exponent where it helps (1e-10, 0.45, 3.2e+05).
std::string number(double value);

[[noreturn]] void fail(const std::string& parameter, double value, const std::string& valid_range);

void finite(const std::string& parameter, double value);
void finite(const std::string& parameter, Vec2 value);
void positive(const std::string& parameter, double value);      // 0 < value < inf
void non_negative(const std::string& parameter, double value);  // 0 <= value < inf
void in_open_unit(const std::string& parameter, double value);  // 0 < value < 1
void tolerance(const std::string& parameter, double value);     // kMinTolerance <= value < 1 (on G)

// Physical scales (lidar_overlap/core/limits.hpp): a length in [kMinLength, kMaxLength] m, a coordinate
// (offset, defocus) within +-kMaxLength m, an angle within +-kMaxAngle rad.
void length(const std::string& parameter, double value);
void coordinate(const std::string& parameter, double value);
void coordinate(const std::string& parameter, Vec2 value);
void angle(const std::string& parameter, double value);
void angle(const std::string& parameter, Vec2 value);

// x rounded down to a size without undefined behaviour: negative gives 0; NaN and anything beyond 2^62 give
// 2^62 (so that a bound checked afterwards fails loudly instead of wrapping).
std::size_t saturate(double x);

// A count derived from a floating-point estimate (samples, panels, steps): the estimate must be finite and
// at most `limit`, else the error names the user's `parameter` and its `value`, and says `why` it leads
// there and how to stay within the limit.
std::size_t count_from(double estimate, std::size_t limit, const std::string& parameter,
                       double value, const std::string& why);

// `copies` n x n grids of `bytes_per_point` bytes each: n <= kMaxGridSide and the total within
// max_memory(), else the error names `parameter` (whose value is n) with the memory needed.
void grid(const std::string& parameter, std::size_t n, std::size_t bytes_per_point,
          std::size_t copies = 1);

// Bytes a call will allocate, against max_memory(); the error names `parameter` and its `value`.
void memory(const std::string& parameter, double value, double bytes, const std::string& fix);

// Overlap values leaving an engine: each must be finite and within [-slack, 1 + slack] (slack: the
// engine's stated accuracy), else std::domain_error naming the range; values within the slack are clipped
// into [0, 1]. `cause`, if given, adds what went wrong at range i (e.g. a sampling loss and its fix).
void overlap_values(std::vector<double>& overlap, const std::vector<double>& ranges, double slack,
                    const std::string& method,
                    const std::function<std::string(std::size_t)>& cause = nullptr);
// The same with a slack per value (a batch of independent computations, each with its own accuracy).
void overlap_values(std::vector<double>& overlap, const std::vector<double>& ranges,
                    const std::vector<double>& slack, const std::string& method,
                    const std::function<std::string(std::size_t)>& cause = nullptr);

}  // namespace lidar_overlap::checks
