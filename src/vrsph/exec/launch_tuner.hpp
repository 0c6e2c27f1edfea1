// Whether a short loop runs on the team of threads or on the calling thread alone, chosen per
// call site and loop size by timing both on the machine at hand (exec/parallel.hpp).
//
// Opening a parallel region and joining it costs a few microseconds (about 2 us per region on two
// threads of an AMD EPYC, docs/validation.md), and a loop whose particles the other core last
// wrote reads them across the cores first. A per-particle loop over a level of a few thousand
// particles (a VR drop's levels: 830 and 2,930) does 5-10 us of work, so whether a second thread
// pays depends on the machine: on an AMD EPYC (Zen 5) running such loops on one thread made the
// VR drop 7% faster, on an Intel Xeon 7% slower. So each call site measures: for loops of fewer
// than 2^16 indices, grouped by the bit width of n, the first calls alternate between the team
// and the calling thread (kTrials timed calls each), then the faster best time wins, and the trial
// is repeated every kRetrial calls in case the machine's load changed. Larger loops and runs on one
// thread are never timed. A call site is tuned by the first thread that launches there; launches
// from any other thread (a program that runs simulations from several threads) take the team.
// One tuner per call site, not per thread: thread_local tuners, copied into every OpenMP
// thread's storage, cost 2 bytes per particle on the 3D dam break (198 -> 200 B).
//
// Only where the chosen threads run, never what a loop computes: every exec loop is in gather
// form (each index writes only its own entries, and reductions are order-independent), so a loop
// gives the same bits on one thread as on the team.
//
// Only the cheap static launches are tuned (for_each, for_each_range, any_of, first_index). Those
// tagged exec::in_shares (exec/parallel.hpp), whose per-particle writes the next neighbour pass
// reads share by share, are tuned only below 2^11 indices. A trial times the loop, not what
// follows it: a loop run on one thread leaves the other thread's share in its own core's cache,
// and the pass after it pays for that, the more the larger the level. Measured on two threads of
// an AMD EPYC (docs/validation.md): with the gather and dynamic launches tuned too, the uniform
// drop of issue #19 (5,027 particles) ran 10% slower; with the sort's permutations, the packing
// and the integrator tuned at every size, 9% slower than with them on the team; tuned below 2^11,
// the three-level impact case (levels of a few hundred to 1,500 particles) runs in 0.65 of the
// time with every loop on the team, against 0.80 with the in_shares loops always on the team.
#pragma once

#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <chrono>
#include <cstdint>
#include <limits>
#include <optional>
#include <string_view>
#include <thread>

namespace vrsph::exec {

// How every call site launches its loops: by measurement (the default), always on the team, or
// always on the calling thread (tests and benchmarks set the last two).
enum class LaunchPolicy : int { tuned, team, alone };

// The policy of a name ("tuned", "team", "alone": the values of the environment variable
// VRSPH_LAUNCH, which the command reads), or none.
inline std::optional<LaunchPolicy> launch_policy_named(std::string_view name) {
  if (name == "tuned") return LaunchPolicy::tuned;
  if (name == "team") return LaunchPolicy::team;
  if (name == "alone") return LaunchPolicy::alone;
  return std::nullopt;
}
inline std::atomic<int>& launch_policy_slot() {
  static std::atomic<int> policy{static_cast<int>(LaunchPolicy::tuned)};
  return policy;
}
inline LaunchPolicy launch_policy() {
  return static_cast<LaunchPolicy>(launch_policy_slot().load(std::memory_order_relaxed));
}
inline void set_launch_policy(LaunchPolicy p) {
  launch_policy_slot().store(static_cast<int>(p), std::memory_order_relaxed);
}

// One launch's choice, and its start time while the call site is on trial.
struct Launch {
  bool alone = false;
  int size_class = -1;  // -1: not timed
  std::int64_t start_ns = 0;
};

class LaunchTuner {
 public:
  static constexpr int kTunedBits = 16;     // loops of n < 2^16 indices are tuned
  static constexpr int kInSharesBits = 11;  // exec::in_shares loops: n < 2^11 only
  static constexpr int kTrials = 8;         // timed calls of each kind per trial
  static constexpr int kRetrial = 4096;     // calls of a size class between trials

  // The choice for a loop of n indices, called by the thread that launches it. Only the first
  // thread to launch at this call site tunes it; a launch from any other thread takes the team.
  Launch begin(std::int64_t n, int tuned_bits = kTunedBits) {
    const LaunchPolicy p = launch_policy();
    if (p != LaunchPolicy::tuned) return {p == LaunchPolicy::alone};
    if (omp_get_max_threads() == 1) return {true};
    if (n >= (std::int64_t{1} << tuned_bits) || omp_in_parallel() || !owned()) return {false};
    const int c = std::bit_width(static_cast<std::uint64_t>(n));
    Class& k = classes_[static_cast<std::size_t>(c)];
    if (k.trial_left == 0) {  // decided
      if (++k.calls_since < kRetrial) return {k.alone};
      k.calls_since = 0;
      k.trial_left = 2 * kTrials;
    }
    return {k.trial_left % 2 == 0, c, now_ns()};  // alternate, alone first
  }

  // After the loop: records a timed launch, and decides once a trial is complete.
  void end(const Launch& l) {
    if (l.size_class < 0) return;
    Class& k = classes_[static_cast<std::size_t>(l.size_class)];
    const auto dt = static_cast<std::int32_t>(
        std::min<std::int64_t>(now_ns() - l.start_ns, std::numeric_limits<std::int32_t>::max()));
    std::int32_t& best = l.alone ? k.best_alone : k.best_team;
    best = std::min(best, dt);
    if (--k.trial_left > 0) return;
    k.alone = k.best_alone < k.best_team;
    k.best_alone = k.best_team = std::numeric_limits<std::int32_t>::max();
  }

 private:
  // A size class: 16 bytes, so that the tuners of some 90 call sites (2D and 3D) hold 25 kB. Each
  // kind keeps its fastest timed launch of the trial (interruptions only lengthen a launch).
  struct Class {
    std::int16_t trial_left = 2 * kTrials;  // timed launches still to make; 0: decided
    bool alone = false;
    std::int32_t calls_since = 0;
    std::int32_t best_alone = std::numeric_limits<std::int32_t>::max();  // ns
    std::int32_t best_team = std::numeric_limits<std::int32_t>::max();
  };

  // Whether the calling thread tunes this call site: the first one to ask does.
  bool owned() {
    const std::thread::id me = std::this_thread::get_id();
    if (owner_.load(std::memory_order_relaxed) == me) return true;
    std::thread::id none{};
    return owner_.compare_exchange_strong(none, me, std::memory_order_relaxed);
  }

  static std::int64_t now_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
  }
  std::atomic<std::thread::id> owner_{};
  std::array<Class, kTunedBits + 1> classes_{};
};

}  // namespace vrsph::exec
