// The execution layer: how a pass runs over particles. This header holds the only thread-level
// OpenMP pragmas of the project; a pass is a functor called for one index i, writing only the
// entries of i (gather form), so its result does not depend on the thread count or schedule.
// The functors own no allocation, virtual call or std::function inside the loop, so the same
// bodies can later be launched by a CUDA back end implementing these few entry points.
#pragma once

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>

#include "vrsph/exec/launch_tuner.hpp"

namespace vrsph::exec {

// Threads a launch uses (OpenMP's current maximum), and a way to set it (--threads).
inline int thread_count() { return omp_get_max_threads(); }
inline void set_thread_count(int n) { omp_set_num_threads(n); }

// body(i) for every i in [0, n), in equal static blocks: cheap, uniform per-particle work.
// The static launches (for_each, for_each_range, any_of, first_index) run short loops on the team
// or on the calling thread alone, as their call site's LaunchTuner chose by timing both
// (exec/launch_tuner.hpp); the result is the same.
template <class Body>
inline void team_for_each(std::int64_t n, Body&& body) {
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) body(i);
}

// for_each over [0, n) on the team or alone, as its call site's tuner chose for loops of fewer
// than 2^kBits indices. The tuner is one per call site: Body is the call site's own lambda type.
template <int kBits, class Body>
inline void tuned_for_each(std::int64_t n, Body&& body) {
  static LaunchTuner tuner;
  const Launch l = tuner.begin(n, kBits);
  if (l.alone) {
    for (std::int64_t i = 0; i < n; ++i) body(i);
  } else {
    team_for_each(n, body);
  }
  tuner.end(l);
}

template <class Body>
inline void for_each(std::int64_t n, Body&& body) {
  tuned_for_each<LaunchTuner::kTunedBits>(n, body);
}

// The tag of a loop whose per-particle writes the next neighbour pass reads share by share (the
// sort's permutations, the packed columns, fields the next sweep reads): on levels of 2^11
// particles or more it always runs on the team, so that each share is written by the core that
// reads it next; a trial would time the loop alone, not that read (exec/launch_tuner.hpp).
struct InShares {};
inline constexpr InShares in_shares{};

template <class Body>
inline void for_each(InShares, std::int64_t n, Body&& body) {
  tuned_for_each<LaunchTuner::kInSharesBits>(n, body);
}

// Thread t's share of [0, n) among nt threads: the contiguous range OpenMP's schedule(static)
// gives it, so that a gather pass finds in its own cache what the static per-particle loops
// (for_each, for_each_range) last wrote.
inline std::int64_t static_share_begin(std::int64_t n, int t, int nt) {
  const std::int64_t q = n / nt, r = n % nt;
  return t * q + std::min<std::int64_t>(t, r);
}

// body(a, b) for consecutive ranges [a, b) of at most `block` indices covering [0, n): each
// thread walks its static share (static_share_begin, the range for_each gives it) in blocks.
// For cheap per-particle loops written over a range with raw pointers, so that the compiler
// vectorises them (a body per index through vector members reloads their pointers after every
// store and stays scalar). Whole-range blocks dealt out by schedule(static) would give one
// thread two of a 5,027-particle drop's three 2,048-blocks, most of them written by the other.
template <class Body>
inline void team_for_each_range(std::int64_t n, std::int64_t block, Body&& body) {
#pragma omp parallel
  {
    const int nt = omp_get_num_threads(), t = omp_get_thread_num();
    const std::int64_t end = static_share_begin(n, t + 1, nt);
    for (std::int64_t a = static_share_begin(n, t, nt); a < end; a += block)
      body(a, std::min(end, a + block));
  }
}

// for_each_range on the team or alone, as tuned_for_each.
template <int kBits, class Body>
inline void tuned_for_each_range(std::int64_t n, std::int64_t block, Body&& body) {
  static LaunchTuner tuner;
  const Launch l = tuner.begin(n, kBits);
  if (l.alone) {
    for (std::int64_t a = 0; a < n; a += block) body(a, std::min(n, a + block));
  } else {
    team_for_each_range(n, block, body);
  }
  tuner.end(l);
}

template <class Body>
inline void for_each_range(std::int64_t n, std::int64_t block, Body&& body) {
  tuned_for_each_range<LaunchTuner::kTunedBits>(n, block, body);
}

template <class Body>
inline void for_each_range(InShares, std::int64_t n, std::int64_t block, Body&& body) {
  tuned_for_each_range<LaunchTuner::kInSharesBits>(n, block, body);
}

// body(i) for every i in [0, n), handed out in chunks of `chunk` consecutive indices: neighbour
// passes, whose cost varies per particle. Consecutive indices share cells after the sort.
template <class Body>
inline void for_each_dynamic(std::int64_t n, int chunk, Body&& body) {
#pragma omp parallel for schedule(dynamic, chunk)
  for (std::int64_t i = 0; i < n; ++i) body(i);
}

// A chunk counter on a cache line of its own.
struct alignas(64) ChunkCounter {
  std::atomic<std::int64_t> next{0};
};

// body(i, scratch, acc) with one Scratch (reused buffers, e.g. a candidate block) and one Acc per
// thread; the threads' Acc are combined with Acc::merge into the result. Acc::merge must be
// order-independent (maxima, integer sums) for the result to be independent of the threads.
// Schedule: each thread takes chunks of `chunk` indices from the front of its static share
// first, then from the other shares in turn (work stealing). A particle is then handled by the
// same thread in every pass unless its thread fell behind, which keeps its data in one core's
// cache; a plain dynamic schedule hands chunks out at random and moves about half the data
// between cores at every pass.
template <class Scratch, class Acc, class Body>
inline Acc for_each_gather(std::int64_t n, int chunk, Body&& body) {
  Acc total{};
  const int max_threads = thread_count();
  std::unique_ptr<ChunkCounter[]> counters(new ChunkCounter[max_threads]);
#pragma omp parallel
  {
    const int nt = omp_get_num_threads(), t = omp_get_thread_num();
    Scratch scratch{};
    Acc acc{};
    for (int k = 0; k < nt; ++k) {
      const int r = (t + k) % nt;  // own share first, then the others
      const std::int64_t b = static_share_begin(n, r, nt), e = static_share_begin(n, r + 1, nt);
      for (;;) {
        const std::int64_t i0 = b + counters[r].next.fetch_add(chunk, std::memory_order_relaxed);
        if (i0 >= e) break;
        const std::int64_t i1 = std::min(e, i0 + chunk);
        for (std::int64_t i = i0; i < i1; ++i) body(i, scratch, acc);
      }
    }
#pragma omp critical(vrsph_exec_merge)
    total.merge(acc);
  }
  return total;
}

// body(i, scratch) with one Scratch per thread and nothing to combine.
template <class Scratch, class Body>
inline void for_each_with(std::int64_t n, int chunk, Body&& body) {
  struct Nothing {
    void merge(const Nothing&) {}
  };
  for_each_gather<Scratch, Nothing>(
      n, chunk, [&](std::int64_t i, Scratch& scratch, Nothing&) { body(i, scratch); });
}

// The largest of `floor` and body(i) over i in [0, n), in chunks as for_each_gather; a maximum,
// so the same for any thread count. body may also write the entries of i (gather form).
template <class Body>
inline double max_of(std::int64_t n, int chunk, double floor, Body&& body) {
  struct Max {
    double v = -1e300;
    void merge(const Max& o) { v = std::max(v, o.v); }
  };
  struct None {};
  const Max m = for_each_gather<None, Max>(
      n, chunk, [&](std::int64_t i, None&, Max& acc) { acc.v = std::max(acc.v, body(i)); });
  return std::max(floor, m.v);
}

// Whether pred(i) holds for some i in [0, n): chunks of `chunk` indices, and once a thread has
// found one the chunks still to start are skipped. The answer (not the i) is the same for any
// thread count.
template <class Pred>
inline bool any_of(std::int64_t n, std::int64_t chunk, Pred&& pred) {
  static LaunchTuner tuner;
  const Launch l = tuner.begin(n);
  if (l.alone) {
    bool hit = false;
    for (std::int64_t i = 0; i < n && !hit; ++i) hit = pred(i);
    tuner.end(l);
    return hit;
  }
  const std::int64_t chunks = (n + chunk - 1) / chunk;
  int found = 0;
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t c = 0; c < chunks; ++c) {
    int seen;
#pragma omp atomic read relaxed
    seen = found;
    if (seen != 0) continue;
    const std::int64_t end = std::min(n, (c + 1) * chunk);
    for (std::int64_t i = c * chunk; i < end; ++i) {
      if (!pred(i)) continue;
#pragma omp atomic write relaxed
      found = 1;
      break;
    }
  }
  tuner.end(l);
  return found != 0;
}

// The lowest i in [0, n) with pred(i), or n when there is none: the same answer for any thread
// count (diagnoses name the same particle).
template <class Pred>
inline std::int64_t first_index(std::int64_t n, Pred&& pred) {
  static LaunchTuner tuner;
  const Launch l = tuner.begin(n);
  std::int64_t first = n;
  if (l.alone) {
    for (std::int64_t i = 0; i < n && first == n; ++i)
      if (pred(i)) first = i;
  } else {
#pragma omp parallel for schedule(static) reduction(min : first)
    for (std::int64_t i = 0; i < n; ++i) {
      if (pred(i)) first = std::min(first, i);
    }
  }
  tuner.end(l);
  return first;
}

}  // namespace vrsph::exec
