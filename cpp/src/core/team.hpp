// The team that shares the blocks of one large pass (the 2-D transforms and the products fused into
// them): the calling thread and the workers of a process-wide pool, which wait for work by spinning
// for a while and then sleep, as FFTW's own threads do. GNU OpenMP lets an idle thread spin for
// GOMP_SPINCOUNT (300 000 pauses by default, 7.6 ms on the 2-core AMD EPYC of docs/reliability.md)
// before it sleeps: free on an idle machine, but on a busy one each region's idle thread takes
// scheduler time from the working ones. Loops over ranges and realisations stay on OpenMP
// (core/parallel.hpp). Internal header, not installed.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>

#include "core/cancel_every.hpp"
#include "core/parallel.hpp"

namespace lidar_overlap::detail {

// How long an idle team thread, or a calling thread whose team has not finished, spins before it
// sleeps. On an idle machine, long against the gaps between the passes of one call and between the
// calls of a loop (microseconds to a millisecond): waking a sleeping thread costs 0.1-0.4 ms on a
// virtual machine whose idle core has halted, and a spinning thread takes a core nobody else wants.
// On a busy machine (machine_busy(), core/parallel.hpp), or in a team of more threads than cores,
// only the gap between the passes of one call: a spinning thread there takes scheduler time from
// the working ones, and a thread that slept is run first when woken.
inline constexpr std::chrono::microseconds kIdleMachineSpin{4000};
inline constexpr std::chrono::microseconds kBusyMachineSpin{50};

// A callable by reference, for the pool's workers (no allocation per call, unlike std::function).
class TeamWork {
 public:
  template <class F>
  explicit TeamWork(F& f)
      : object_(&f), call_([](void* o, int member) { (*static_cast<F*>(o))(member); }) {}
  void operator()(int member) const { call_(object_, member); }

 private:
  void* object_;
  void (*call_)(void*, int);
};

// work(0) on the calling thread and work(member) on each of up to threads - 1 pool workers (members
// 1 .. threads - 1) that starts before work(0) has returned: a worker the machine runs later skips
// the call, so a call never waits for a thread that has not started (on a busy machine it may wait
// several scheduler time slices for a core), only for those still in their work. Returns when every
// member that started has returned, and rethrows the first exception one of them threw. With
// threads <= 1, or while another thread's team holds the pool (two callers at once), the calling
// thread alone runs work(0). So the work must be shared dynamically and done in full by whichever
// members run (for_each_block), never assigned to a member. A worker's late start (also one that
// skips the call), time descheduled in the work and the caller's wait for the others are measured
// and reported (TeamClock, note_team_wait): they mark the machine busy, which shortens the spins.
void run_team(int threads, const TeamWork& work);

// The member index of the calling thread in the team it works in (0 outside a team): per-thread
// sums.
int team_member();

// body(b) for every block b in [0, blocks), handed out one at a time to the `threads` threads of a
// team (run_team), so that a thread the machine delays holds up one block, not a share of the pass.
// The caller's CancelScope is asked before each block (RegionStop): once it stops, the blocks left
// are skipped and Cancelled (or the scope's own exception) is thrown after the team has ended.
template <class Body>
void for_each_block(long blocks, int threads, Body&& body) {
  std::atomic<long> next{0};
  RegionStop stop;
  auto work = [&](int) {
    for (long b = next.fetch_add(1, std::memory_order_relaxed); b < blocks && !stop.stopped();
         b = next.fetch_add(1, std::memory_order_relaxed))
      body(b);
  };
  run_team(threads, TeamWork(work));
  stop.rethrow();
}

}  // namespace lidar_overlap::detail
