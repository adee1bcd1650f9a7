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

namespace {
// Until when (steady clock, ns) `threads = 0` means one thread: set when a team's threads waited for a core.
std::atomic<long long> g_busy_until_ns{0};

// A team one of whose threads waited this long for a core (and this share of the region) waited for the
// machine: on an idle one threads start within tens of microseconds and run undisturbed.
constexpr long long kLongWaitNs = 1'000'000;
constexpr double kLongWaitShare = 0.25;
// How long such a wait holds all-core calls to one thread before a team is tried again: 0.1 s after a
// first wait, doubled by each wait within twice the last hold up to 1 s, long against the cost of a late
// team (a few scheduler time slices) and short against a change of load. A virtual machine's host takes a
// core for 1-3 ms in bursts every few seconds; a second-long hold after each kept a quiet machine's loop of
// 512^2 propagations on one thread half of the time.
constexpr long long kFirstHoldOffNs = 100'000'000, kLongestHoldOffNs = 1'000'000'000;
std::atomic<long long> g_hold_off_ns{kFirstHoldOffNs};
}  // namespace

void note_team_wait(int threads, long long waited_ns, long long region_ns) {
  if (threads < 2 || waited_ns < kLongWaitNs || waited_ns < kLongWaitShare * region_ns) return;
  const long long now = steady_ns(), last = g_hold_off_ns.load(std::memory_order_relaxed),
                  until = g_busy_until_ns.load(std::memory_order_relaxed);
  const long long hold =
      now < until + last ? std::min(2 * last, kLongestHoldOffNs) : kFirstHoldOffNs;
  g_hold_off_ns.store(hold, std::memory_order_relaxed);
  g_busy_until_ns.store(now + hold, std::memory_order_relaxed);
}

bool machine_busy() { return steady_ns() < g_busy_until_ns.load(std::memory_order_relaxed); }

int all_cores() { return machine_busy() ? 1 : all_cores_even_if_busy(); }

int all_cores_even_if_busy() { return std::min(omp_get_max_threads(), max_threads()); }

int thread_count(int requested) {
  if (requested < 0 || requested > max_threads())
    checks::fail("threads", requested,
                 "0 (all cores) or a count from 1 to " + std::to_string(max_threads()) +
                     " (4 per core, at least 256)");
  return requested > 0 ? requested : all_cores();
}

}  // namespace detail
}  // namespace lidar_overlap
