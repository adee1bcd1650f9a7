#include "core/entry_checks.hpp"

#include <stdexcept>

#include "core/parallel.hpp"
#include "lidar_overlap/core/parameter_error.hpp"

namespace lidar_overlap::detail {

std::string range_name(std::size_t i) { return "ranges[" + std::to_string(i) + "]"; }

int checked_threads_and_ranges(const LidarSystem& system, const std::vector<double>& ranges,
                               int threads) {
  const int team = thread_count(threads);
  for (std::size_t i = 0; i < ranges.size(); ++i) system.validate_range(ranges[i], range_name(i));
  return team;
}

int checked_threads_and_ranges(const std::vector<LidarSystem>& systems,
                               const std::vector<double>& ranges, int threads) {
  const int team = thread_count(threads);
  for (std::size_t i = 0; i < systems.size(); ++i) {
    try {
      systems[i].validate();
    } catch (const ParameterError& e) {
      const std::string item = "systems[" + std::to_string(i) + "]";
      throw ParameterError(item + ": " + e.what(), item + "." + e.parameter(), e.value(),
                           e.expected());
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("systems[" + std::to_string(i) + "]: " + e.what());
    }
    systems[i].validate_range(ranges[i], range_name(i));
  }
  return team;
}

}  // namespace lidar_overlap::detail
