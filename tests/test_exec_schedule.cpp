// exec::for_each_gather's schedule: every thread starts on its own static share and then takes
// chunks of the others' (work stealing). Whatever the thread count, the chunk size and the
// imbalance, every index must be visited exactly once, each thread's accumulator merged once,
// and a thread that is not held up must sweep its own share itself. Then the choice between the
// team and the calling thread alone (exec/launch_tuner.hpp): the same results either way, and
// the tuner takes whichever is faster.
#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <thread>
#include <vector>

#include "vrsph/exec/parallel.hpp"

namespace vrsph {
namespace {

struct Count {
  std::int64_t visits = 0, merges = 0;
  void merge(const Count& o) { visits += o.visits, merges += o.merges + 1; }
};
struct NoScratch {};

// Restores the thread count a test changed.
struct Threads {
  int saved = exec::thread_count();
  explicit Threads(int n) { exec::set_thread_count(n); }
  ~Threads() { exec::set_thread_count(saved); }
};

// Sets the launch policy for a test and restores it. The schedule tests below need the team.
struct Policy {
  exec::LaunchPolicy saved = exec::launch_policy();
  explicit Policy(exec::LaunchPolicy p) { exec::set_launch_policy(p); }
  ~Policy() { exec::set_launch_policy(saved); }
};

TEST(ExecSchedule, EveryIndexOnceForAnyThreadsAndChunk) {
  const Policy team(exec::LaunchPolicy::team);
  for (int threads : {1, 2, 3, 5}) {
    const Threads t(threads);
    for (std::int64_t n : {0, 1, 2, 7, 64, 1000, 4099}) {
      for (int chunk : {1, 3, 64, 512}) {
        std::vector<std::atomic<int>> seen(static_cast<std::size_t>(n));
        const Count c = exec::for_each_gather<NoScratch, Count>(
            n, chunk, [&](std::int64_t i, NoScratch&, Count& acc) {
              seen[static_cast<std::size_t>(i)].fetch_add(1, std::memory_order_relaxed);
              ++acc.visits;
            });
        EXPECT_EQ(c.visits, n) << threads << " threads, n " << n << ", chunk " << chunk;
        EXPECT_EQ(c.merges, omp_get_max_threads()) << "one accumulator per thread";
        for (std::int64_t i = 0; i < n; ++i)
          ASSERT_EQ(seen[static_cast<std::size_t>(i)].load(), 1)
              << "index " << i << ", " << threads << " threads, n " << n << ", chunk " << chunk;
      }
    }
  }
}

// The static shares are those of OpenMP's schedule(static) (exec::for_each), so the gather
// passes sweep a particle on the core whose loops last wrote it.
TEST(ExecSchedule, SharesAreTheStaticSchedule) {
  const Policy team(exec::LaunchPolicy::team);
  for (int nt : {1, 2, 3, 4}) {
    const Threads t(nt);
    for (std::int64_t n : {0, 1, 5, 10, 1001}) {
      std::vector<int> owner(static_cast<std::size_t>(n), -1);
      exec::for_each(n, [&](std::int64_t i) { owner[i] = omp_get_thread_num(); });
      if (omp_get_max_threads() != nt) continue;  // the runtime gave fewer threads
      for (int r = 0; r < nt; ++r) {
        for (std::int64_t i = exec::static_share_begin(n, r, nt);
             i < exec::static_share_begin(n, r + 1, nt); ++i)
          EXPECT_EQ(owner[static_cast<std::size_t>(i)], r) << "n " << n << ", index " << i;
      }
      EXPECT_EQ(exec::static_share_begin(n, nt, nt), n);
    }
  }
}

// Thread 1 held up in its first chunk: thread 0 sweeps its own share and then takes the rest of
// thread 1's, so the pass does not wait for the slow thread's whole share.
TEST(ExecSchedule, AFreeThreadTakesTheChunksOfOneHeldUp) {
  const Policy team(exec::LaunchPolicy::team);
  const Threads t(2);
  if (omp_get_max_threads() != 2) GTEST_SKIP() << "needs two OpenMP threads";
  constexpr std::int64_t n = 400, chunk = 10;
  std::vector<std::atomic<int>> who(n);
  for (auto& w : who) w = -1;
  std::atomic<bool> held{false}, released{false};
  std::atomic<std::int64_t> done0{0};
  auto wait_for = [](const std::atomic<bool>& flag) {
    for (int k = 0; k < 5000 && !flag.load(); ++k)  // at most 5 s
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
  };
  exec::for_each_gather<NoScratch, Count>(n, chunk, [&](std::int64_t i, NoScratch&, Count&) {
    const int me = omp_get_thread_num();
    if (me == 1 && !held.exchange(true)) wait_for(released);
    if (me == 0) wait_for(held);  // thread 1 has taken its first chunk
    who[static_cast<std::size_t>(i)] = me;
    if (me == 0 && ++done0 == n - chunk) released = true;
  });
  std::int64_t by0 = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    const int w = who[static_cast<std::size_t>(i)];
    ASSERT_NE(w, -1) << "index " << i << " not visited";
    by0 += w == 0;
    // thread 0's own share, and thread 1's first chunk, stay with their owners
    if (i < n / 2) {
      EXPECT_EQ(w, 0) << "index " << i;
    } else if (i < n / 2 + chunk) {
      EXPECT_EQ(w, 1) << "index " << i;
    }
  }
  EXPECT_EQ(by0, n - chunk);
}

// Every launch gives the same result on the team and on the calling thread alone, and with the
// tuner choosing between them call by call.
TEST(ExecLaunch, SameResultsAloneOnTheTeamAndTuned) {
  const Threads t(3);
  for (std::int64_t n : {0, 1, 7, 1000, 70000}) {
    std::vector<std::vector<std::int64_t>> got;
    for (auto p :
         {exec::LaunchPolicy::team, exec::LaunchPolicy::alone, exec::LaunchPolicy::tuned}) {
      const Policy policy(p);
      for (int call = 0; call < 20; ++call) {  // the tuned launches alternate while on trial
        std::vector<std::int64_t> v(static_cast<std::size_t>(n), 0), r;
        exec::for_each(n, [&](std::int64_t i) { v[i] += i + 1; });
        exec::for_each_range(n, 64, [&](std::int64_t a, std::int64_t b) {
          for (std::int64_t i = a; i < b; ++i) v[i] += 2 * i + 2;
        });
        exec::for_each_dynamic(n, 16, [&](std::int64_t i) { v[i] += 3 * i + 3; });
        exec::for_each(exec::in_shares, n, [&](std::int64_t i) { v[i] += 5 * i + 5; });
        exec::for_each_range(exec::in_shares, n, 32, [&](std::int64_t a, std::int64_t b) {
          for (std::int64_t i = a; i < b; ++i) v[i] += 6 * i + 6;
        });
        exec::for_each_with<NoScratch>(n, 8,
                                       [&](std::int64_t i, NoScratch&) { v[i] += 4 * i + 4; });
        const Count c = exec::for_each_gather<NoScratch, Count>(
            n, 8, [&](std::int64_t, NoScratch&, Count& acc) { ++acc.visits; });
        r = v;
        r.push_back(c.visits);
        r.push_back(static_cast<std::int64_t>(
            exec::max_of(n, 8, -1.0, [](std::int64_t i) { return static_cast<double>(i % 977); })));
        r.push_back(exec::any_of(n, 4, [n](std::int64_t i) { return i == n / 2; }));
        r.push_back(exec::first_index(n, [](std::int64_t i) { return i % 300 == 299; }));
        if (!got.empty()) {
          ASSERT_EQ(r, got.front()) << "n " << n << ", policy " << static_cast<int>(p);
        }
        got.push_back(r);
      }
    }
  }
}

// Spins for `us` microseconds.
void spin_us(int us) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::microseconds(us);
  while (std::chrono::steady_clock::now() < end) {
  }
}

// Launches of one call site (one per Site) whose body spins 200 us once per launch when it runs on
// the team (slow_team) or alone; returns how many of the launches after the trial ran alone.
template <int Site>
int alone_after_trial(bool slow_team, int calls) {
  int alone = 0;
  for (int call = 0; call < calls; ++call) {
    std::atomic<int> on_team{0};
    exec::for_each(100, [&](std::int64_t i) {
      const bool team = omp_in_parallel() != 0;
      if (i == 0 && team == slow_team) spin_us(200);
      if (team) on_team = 1;
    });
    if (call >= 2 * exec::LaunchTuner::kTrials) alone += on_team == 0;
  }
  return alone;
}

// A call site whose loops are slower on the team runs them alone after its trial, and one whose
// loops are slower alone keeps the team.
TEST(ExecLaunch, TunerTakesTheFasterWay) {
  const Threads t(2);
  if (omp_get_max_threads() != 2) GTEST_SKIP() << "needs two OpenMP threads";
  const Policy tuned(exec::LaunchPolicy::tuned);
  constexpr int calls = 40, after = calls - 2 * exec::LaunchTuner::kTrials;
  EXPECT_EQ(alone_after_trial<0>(true, calls), after) << "the team was slower";
  EXPECT_EQ(alone_after_trial<1>(false, calls), 0) << "alone was slower";
}

}  // namespace
}  // namespace vrsph
