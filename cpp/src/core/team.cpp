#include "core/team.hpp"

#include <omp.h>
#include <pthread.h>

#include <algorithm>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace lidar_overlap::detail {

namespace {

thread_local int t_member = 0;
// This thread runs a team: a team of its own would be run alone.
thread_local bool t_calling = false;

// A generation of work and its number of helpers in one word, so that a worker reads both at once.
constexpr int kHelperBits = 20;
constexpr std::uint64_t kHelperMask = (std::uint64_t{1} << kHelperBits) - 1;
// The gate of a generation: the helpers inside it (low bits), whether the caller has closed it, and
// the generation (high bits), in one word, so that a helper enters only the open gate of its own
// generation.
constexpr std::uint64_t kInsideMask = (std::uint64_t{1} << (kHelperBits + 1)) - 1;
constexpr std::uint64_t kClosed = std::uint64_t{1} << (kHelperBits + 1);
constexpr int kGateGenerationShift = kHelperBits + 2;
inline std::uint64_t gate_of(std::uint64_t generation) {
  return generation << kGateGenerationShift;
}

// One spin step: a pause on x86 (lets the sibling hyper-thread run and saves power), a yield hint
// on Arm.
inline void spin_pause() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__)
  asm volatile("yield");
#endif
}

// Spins until done() or the spin for this machine's load has passed; true if done. A team of more
// threads than cores (OMP_NUM_THREADS above them) waits as on a busy machine: its own threads are
// the load.
template <class Done>
bool spun_until(int team, Done&& done) {
  static const int cores = omp_get_num_procs();
  const bool busy = team > cores || machine_busy();
  const auto until =
      std::chrono::steady_clock::now() + (busy ? kBusyMachineSpin : kIdleMachineSpin);
  for (;;) {
    for (int i = 0; i < 16; ++i) {
      if (done()) return true;
      spin_pause();
    }
    if (std::chrono::steady_clock::now() >= until) return done();
  }
}

// Workers wait for a new generation of work; the calling thread for the helpers of its generation.
class Pool {
 public:
  // Runs work on the caller and up to threads - 1 workers; false (nothing run) if another team
  // holds the pool.
  bool run(int threads, const TeamWork& work, TeamClock& clock) {
    if (t_calling) return false;
    std::unique_lock<std::mutex> holding(busy_, std::try_to_lock);
    if (!holding.owns_lock()) return false;
    const int helpers = grow(std::min<int>(threads - 1, static_cast<int>(kHelperMask)));
    t_calling = true;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      work_ = &work;
      clock_ = &clock;
      failure_ = nullptr;
      const std::uint64_t generation = (ticket_.load() >> kHelperBits) + 1;
      gate_.store(gate_of(generation));
      published_ns_.store(steady_ns());
      ticket_.store(generation << kHelperBits | static_cast<std::uint64_t>(helpers));
    }
    wake_.notify_all();
    member(0);
    // The caller's share is done, so every block is taken: close the gate, so that a helper the
    // machine has not run yet skips this generation, and wait only for the helpers inside
    // (finishing a block).
    gate_.fetch_or(kClosed);
    const auto all_left = [&] { return (gate_.load() & kInsideMask) == 0; };
    if (!all_left()) {
      const long long waiting = steady_ns();
      if (!spun_until(helpers + 1, all_left)) {
        std::unique_lock<std::mutex> lock(mutex_);
        done_.wait(lock, all_left);
      }
      clock.waited(steady_ns() - waiting);
    }
    t_calling = false;
    if (failure_) std::rethrow_exception(failure_);
    return true;
  }

 private:
  // Workers for `wanted` helpers, made on first need; fewer if the system refuses threads.
  int grow(int wanted) {
    while (static_cast<int>(count_) < wanted) {
      try {
        // It starts from the current generation: one published before it runs is still its to
        // serve.
        std::thread(&Pool::serve, this, static_cast<int>(count_) + 1, ticket_.load()).detach();
      } catch (const std::system_error&) {
        break;
      }
      ++count_;
    }
    return std::min(wanted, static_cast<int>(count_));
  }

  void member(int index) {
    t_member = index;
    const TeamClock::Mark mark = clock_->started();  // a late start marks the machine busy
    try {
      (*work_)(index);
    } catch (...) {
      std::lock_guard<std::mutex> lock(failure_mutex_);
      if (!failure_) failure_ = std::current_exception();
    }
    clock_->finished(mark);
    t_member = 0;
  }

  // A worker's life: wait for a generation (spin, then sleep), take part if its index is among the
  // helpers.
  void serve(int index, std::uint64_t seen) {
    for (;;) {
      if (!spun_until(static_cast<int>(seen & kHelperMask) + 1,
                      [&] { return ticket_.load() != seen; })) {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return ticket_.load() != seen; });
      }
      seen = ticket_.load();
      if (static_cast<std::uint64_t>(index) > (seen & kHelperMask)) continue;
      if (!enter(gate_of(seen >> kHelperBits))) {  // late: the caller has finished the work
        const long long late = steady_ns() - published_ns_.load();
        note_team_wait(static_cast<int>(seen & kHelperMask) + 1, late, late);
        continue;
      }
      member(index);
      const std::uint64_t left = gate_.fetch_sub(1) - 1;
      if ((left & kClosed) && (left & kInsideMask) == 0) {
        {
          std::lock_guard<std::mutex> lock(mutex_);
        }  // the caller is waiting or will see none inside
        done_.notify_one();
      }
    }
  }

  // Into the gate `open` (gate_of a generation), if the gate is still that one and open.
  bool enter(std::uint64_t open) {
    std::uint64_t g = gate_.load();
    while ((g & ~kInsideMask) == open)
      if (gate_.compare_exchange_weak(g, g + 1)) return true;
    return false;
  }

  std::mutex busy_;  // one team at a time
  std::mutex mutex_, failure_mutex_;
  std::condition_variable wake_, done_;   // workers: a new generation; the caller: the gate emptied
  std::atomic<std::uint64_t> ticket_{0};  // generation << kHelperBits | its helpers
  std::atomic<std::uint64_t> gate_{0};    // gate_of(generation) | kClosed | helpers inside
  std::atomic<long long> published_ns_{0};  // when the current generation was published
  const TeamWork* work_ = nullptr;  // written before ticket_ changes, read by its helpers after
  TeamClock* clock_ = nullptr;
  std::size_t count_ = 0;  // workers made (they never end)
  std::exception_ptr failure_;
};

// The pool is never destroyed: its workers sleep through exit. A forked child has none of its
// parent's threads, so it starts a pool of its own (the parent's stays reachable, and unused, in
// the child).
std::atomic<Pool*> g_pool{nullptr};
std::vector<Pool*>* g_forsaken = nullptr;

Pool& pool() {
  static const bool fork_handled = [] {
    pthread_atfork(nullptr, nullptr, [] {
      if (!g_forsaken) g_forsaken = new std::vector<Pool*>();
      g_forsaken->push_back(g_pool.exchange(nullptr));
    });
    return true;
  }();
  (void)fork_handled;
  Pool* p = g_pool.load(std::memory_order_acquire);
  if (p) return *p;
  static std::mutex making;
  std::lock_guard<std::mutex> lock(making);
  p = g_pool.load(std::memory_order_acquire);
  if (!p) {
    p = new Pool();
    g_pool.store(p, std::memory_order_release);
  }
  return *p;
}

}  // namespace

int team_member() { return t_member; }

void run_team(int threads, const TeamWork& work) {
  TeamClock clock;
  if (threads > 1 && pool().run(threads, work, clock)) {
    clock.report(threads);
    return;
  }
  const TeamClock::Mark mark = clock.started();
  work(0);
  clock.finished(mark);
}

}  // namespace lidar_overlap::detail
