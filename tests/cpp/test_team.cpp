// The team that shares a pass's blocks (cpp/src/core/team.hpp): member 0 runs once per call and
// every other member at most once (all of them when member 0 waits for them), every block exactly
// once for any team size (more threads than cores too), no member is still in its work once the
// call has returned, an exception of any member reaches the caller after every member that started
// has returned, two callers at once and a team inside a team's work each complete (one of them
// alone), and a forked child gets a pool of its own. None of it depends on timing: a test that
// hangs instead of failing is stopped by alarm().
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "check.hpp"
#include "core/team.hpp"

using namespace lidar_overlap::detail;

namespace {

// Runs for_each_block over `blocks` on `threads` and says whether every block ran exactly once.
bool every_block_once(long blocks, int threads) {
  std::vector<std::atomic<int>> runs(static_cast<std::size_t>(blocks));
  for (auto& r : runs) r.store(0);
  for_each_block(blocks, threads, [&](long b) { runs[static_cast<std::size_t>(b)].fetch_add(1); });
  for (const auto& r : runs)
    if (r.load() != 1) return false;
  return true;
}

// Spins until `count` reaches `value` (a member waiting for the others to start; alarm() ends a
// hang).
void wait_for(const std::atomic<int>& count, int value) {
  while (count.load() < value) std::this_thread::yield();
}

void members_and_blocks() {
  for (int threads : {1, 2, 3, 5}) {
    const std::string with = " (" + std::to_string(threads) + " threads)";
    std::vector<std::atomic<int>> ran(static_cast<std::size_t>(threads));
    for (auto& r : ran) r.store(0);
    std::atomic<bool> own_index{true};
    std::atomic<int> started{0};
    // Member 0 returns once every member has started: none of them is late, so all run.
    auto work = [&](int member) {
      ran[static_cast<std::size_t>(member)].fetch_add(1);
      if (team_member() != member) own_index.store(false);
      started.fetch_add(1);
      if (member == 0) wait_for(started, threads);
    };
    for (int call = 0; call < 50; ++call) {
      started.store(0);
      run_team(threads, TeamWork(work));
    }
    bool each_fifty = true;
    for (const auto& r : ran) each_fifty = each_fifty && r.load() == 50;
    test::that("every member runs once per call while member 0 waits for them" + with, each_fifty);
    test::that("team_member() is the member's index" + with, own_index.load());
    test::that("team_member() is 0 outside a team" + with, team_member() == 0);

    // Member 0 alone can do the work: the others run at most once per call, and none after it.
    for (auto& r : ran) r.store(0);
    std::atomic<int> inside{0};
    bool none_inside_after = true;
    for (int call = 0; call < 2000; ++call) {
      auto quick = [&](int member) {
        inside.fetch_add(1);
        ran[static_cast<std::size_t>(member)].fetch_add(1);
        inside.fetch_sub(1);
      };
      run_team(threads, TeamWork(quick));
      none_inside_after = none_inside_after && inside.load() == 0;
    }
    bool at_most_once = ran[0].load() == 2000;
    for (const auto& r : ran) at_most_once = at_most_once && r.load() <= 2000;
    test::that("member 0 runs every call, the others at most once" + with, at_most_once);
    test::that("no member is in its work after the call returned" + with, none_inside_after);
    for (long blocks : {0L, 1L, 7L, 1000L})
      test::that("every block once, " + std::to_string(blocks) + " blocks" + with,
                 every_block_once(blocks, threads));
  }
}

void failures_reach_the_caller() {
  for (int thrower : {0, 1}) {
    std::atomic<int> started{0}, finished{0};
    auto work = [&](int member) {
      started.fetch_add(1);
      wait_for(started, 2);  // both run, whichever throws
      if (member == thrower) throw std::runtime_error("member " + std::to_string(member));
      finished.fetch_add(1);
    };
    std::string caught;
    try {
      run_team(2, TeamWork(work));
    } catch (const std::runtime_error& e) {
      caught = e.what();
    }
    const std::string who = "member " + std::to_string(thrower);
    test::that("a throwing " + who + " is rethrown to the caller", caught == who);
    test::that("the other member finished before the rethrow (" + who + ")", finished.load() == 1);
  }
  test::that("the pool works after a failure", every_block_once(100, 2));
}

void callers_at_once_and_nested() {
  std::atomic<bool> all_complete{true};
  auto caller = [&] {
    for (int call = 0; call < 200; ++call)
      if (!every_block_once(64, 2)) all_complete.store(false);
  };
  std::thread a(caller), b(caller);
  a.join();
  b.join();
  test::that("two callers at once: every call covers every block", all_complete.load());

  std::atomic<bool> inner_complete{false};
  auto outer = [&](int member) {
    if (member == 0) inner_complete.store(every_block_once(32, 2));  // the pool is held: runs alone
  };
  run_team(2, TeamWork(outer));
  test::that("a team inside a team's work completes", inner_complete.load());
}

void forked_child() {
  test::that("the parent's pool is running", every_block_once(64, 2));
  const pid_t child = fork();
  if (child == 0) {
    alarm(60);  // a child stuck on its parent's workers ends with SIGALRM, not a hang
    _exit(every_block_once(64, 2) && every_block_once(1000, 3) ? 0 : 1);
  }
  int status = 0;
  test::that("fork", child > 0 && waitpid(child, &status, 0) == child);
  test::that("a forked child runs teams of its own", WIFEXITED(status) && WEXITSTATUS(status) == 0);
  test::that("the parent's pool still runs after the fork", every_block_once(64, 2));
}

}  // namespace

int main() {
  alarm(300);
  members_and_blocks();
  failures_reach_the_caller();
  callers_at_once_and_nested();
  forked_child();
  return test::failures;
}
