// The parallel stable counting sort (particles/key_sort.hpp): the same permutation, key starts
// and dropped list as a plain serial stable sort, for any thread count, on keys that are nearly
// sorted (as after a previous step), on keys in reverse order (every part's window spans the
// whole key range), with dropped particles, and with keys too full for 8- and 16-bit counters.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "vrsph/exec/parallel.hpp"
#include "vrsph/particles/key_sort.hpp"

namespace {

struct Sorted {
  std::vector<std::uint32_t> begin, perm, dropped;
};

Sorted serial_sort(const std::vector<std::uint32_t>& keys, std::size_t nkeys) {
  Sorted s;
  for (std::uint32_t i = 0; i < keys.size(); ++i) {
    if (keys[i] == vrsph::KeySort::kDropped)
      s.dropped.push_back(i);
    else
      s.perm.push_back(i);
  }
  std::stable_sort(s.perm.begin(), s.perm.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
  s.begin.assign(nkeys + 1, 0);
  for (std::uint32_t i : s.perm) ++s.begin[static_cast<std::size_t>(keys[i]) + 1];
  std::partial_sum(s.begin.begin(), s.begin.end(), s.begin.begin());
  return s;
}

std::vector<std::uint32_t> starts_of(const vrsph::KeyStarts& starts, std::size_t nkeys) {
  std::vector<std::uint32_t> begin(nkeys + 1);
  for (std::size_t k = 0; k <= nkeys; ++k) begin[k] = starts[k];
  return begin;
}

void expect_same_for_all_thread_counts(const std::vector<std::uint32_t>& keys, std::size_t nkeys) {
  const Sorted want = serial_sort(keys, nkeys);
  const int before = vrsph::exec::thread_count();
  for (int threads : {1, 2, 3, 7}) {
    vrsph::exec::set_thread_count(threads);
    vrsph::KeySort sorter;
    Sorted got;
    vrsph::KeyStarts starts;
    starts.base.assign(nkeys + 1, 12345);  // stale values must not survive
    starts.off.assign(nkeys + 1, 321);
    sorter.sort(keys, nkeys, starts, got.perm, got.dropped);
    got.begin = starts_of(starts, nkeys);
    EXPECT_EQ(got.perm, want.perm) << threads << " threads";
    EXPECT_EQ(got.begin, want.begin) << threads << " threads";
    EXPECT_EQ(got.dropped, want.dropped) << threads << " threads";
  }
  vrsph::exec::set_thread_count(before);
}

TEST(KeySort, NearlySortedKeysWithDropsMatchASerialStableSort) {
  std::mt19937 rng(7);
  const std::size_t n = 5000, nkeys = 2000;
  std::vector<std::uint32_t> keys(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto base = static_cast<std::int64_t>(i * nkeys / n);  // sorted, several per key
    keys[i] = static_cast<std::uint32_t>(std::clamp<std::int64_t>(
        base + static_cast<std::int64_t>(rng() % 5) - 2, 0, static_cast<std::int64_t>(nkeys) - 1));
    if (rng() % 97 == 0) keys[i] = vrsph::KeySort::kDropped;
  }
  expect_same_for_all_thread_counts(keys, nkeys);
}

TEST(KeySort, ReversedAndRepeatedKeysMatchASerialStableSort) {
  const std::size_t n = 3001, nkeys = 50;
  std::vector<std::uint32_t> keys(n);
  for (std::size_t i = 0; i < n; ++i) keys[i] = static_cast<std::uint32_t>((n - i) % nkeys);
  expect_same_for_all_thread_counts(keys, nkeys);
}

// Keys fuller than a 16-bit counter: one thread overflows its count, seven overflow only the
// key's total (10,000 each); both fall back to 32-bit counters and starts with the same result.
// A second sort with the same sorter on ordinary keys takes the narrow counters and the 16-bit
// offsets again.
TEST(KeySort, KeysHoldingMoreThan65535ParticlesMatchASerialStableSort) {
  std::mt19937 rng(11);
  const std::size_t n = 70000 + 2000, nkeys = 40;
  std::vector<std::uint32_t> keys(n);
  for (std::size_t i = 0; i < n; ++i)
    keys[i] = i % 36 == 0 ? static_cast<std::uint32_t>(rng() % nkeys) : 17;
  expect_same_for_all_thread_counts(keys, nkeys);
  vrsph::KeySort sorter;
  Sorted got;
  vrsph::KeyStarts starts;
  sorter.sort(keys, nkeys, starts, got.perm, got.dropped);
  EXPECT_EQ(starts.shift, 0);     // one 32-bit start per key
  const std::size_t many = 4000;  // 18 particles per key, about 1,150 per run of 64 keys
  std::vector<std::uint32_t> few(n);
  for (std::size_t i = 0; i < n; ++i) few[i] = static_cast<std::uint32_t>(i * many / n);
  sorter.sort(few, many, starts, got.perm, got.dropped);
  EXPECT_EQ(starts.shift, vrsph::KeyStarts::kShift);  // 16-bit offsets again
  EXPECT_EQ(got.perm, serial_sort(few, many).perm);
  EXPECT_EQ(starts_of(starts, many), serial_sort(few, many).begin);
}

// Keys that fit 16-bit counters in a run of keys that does not fit 16-bit offsets: 35,000 and
// 36,000 particles in two neighbouring keys; the starts fall back to 32 bits per key.
TEST(KeySort, RunsHoldingMoreThan65535ParticlesMatchASerialStableSort) {
  const std::size_t n = 35000 + 36000 + 500, nkeys = 300;
  std::vector<std::uint32_t> keys(n);
  for (std::size_t i = 0; i < n; ++i)
    keys[i] = i < 500 ? static_cast<std::uint32_t>(i % 100) : (i < 35500 ? 130 : 131);
  expect_same_for_all_thread_counts(keys, nkeys);
}

// Keys too full for 8-bit counters but not for 16-bit ones: 300 particles of one key, taken
// whole by one thread (its own count overflows) or split over several (only the key's total
// does), between keys of a few particles each.
TEST(KeySort, KeysHoldingMoreThan255ParticlesMatchASerialStableSort) {
  const std::size_t n = 1200, nkeys = 400;
  std::vector<std::uint32_t> keys(n);
  for (std::size_t i = 0; i < n; ++i)
    keys[i] = i >= 450 && i < 750 ? 150 : static_cast<std::uint32_t>(i * nkeys / n);
  expect_same_for_all_thread_counts(keys, nkeys);
}

TEST(KeySort, EmptyAndAllDropped) {
  expect_same_for_all_thread_counts({}, 10);
  expect_same_for_all_thread_counts(std::vector<std::uint32_t>(17, vrsph::KeySort::kDropped), 10);
}

}  // namespace
