#include "lidar_overlap/core/limits.hpp"

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <string>

#include "core/checks.hpp"
#include "core/parallel.hpp"

namespace lidar_overlap {
namespace {
std::atomic<std::size_t> g_max_memory{0};  // 0: the default

std::size_t default_max_memory() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return std::size_t{4} << 30;  // unknown machine: 4 GiB
  return static_cast<std::size_t>(pages) / 4 * static_cast<std::size_t>(page);
}
}  // namespace

std::size_t max_memory() {
  const std::size_t set = g_max_memory.load();
  return set ? set : default_max_memory();
}

void set_max_memory(std::size_t bytes) { g_max_memory.store(bytes); }

int max_threads() { return std::max(256, 4 * omp_get_num_procs()); }

namespace detail {

int thread_count(int requested) {
  if (requested < 0 || requested > max_threads())
    checks::fail("threads", requested,
                 "0 (all cores) or a count from 1 to " + std::to_string(max_threads()) + " (4 per core, at least 256)");
  return requested > 0 ? requested : std::min(omp_get_max_threads(), max_threads());
}

}  // namespace detail
}  // namespace lidar_overlap
