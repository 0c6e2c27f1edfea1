#include "vrsph/particles/key_sort.hpp"

#include <algorithm>
#include <array>
#include <limits>

#include "vrsph/exec/parallel.hpp"

namespace vrsph {

template <class C>
void KeySort::Part::keep_only() {
  if constexpr (sizeof(C) != 1) std::vector<std::uint8_t>().swap(count8);
  if constexpr (sizeof(C) != 2) std::vector<std::uint16_t>().swap(count16);
  if constexpr (sizeof(C) != 4) std::vector<std::uint32_t>().swap(count32);
}

// The key window of one part and its dropped particles: the keys' minimum and maximum as
// reductions the compiler vectorises (kDropped, the largest key, never lowers the minimum and is
// left out of the maximum), the dropped particles, which are rare, collected in a second loop only
// where there are some.
void KeySort::window(const std::vector<std::uint32_t>& keys, Part& part) {
  part.dropped.clear();
  const std::uint32_t* __restrict key = keys.data();
  const std::int64_t first = part.first, last = part.last;
  std::uint32_t lo = kDropped, hi = 0, dropped = 0;
  for (std::int64_t i = first; i < last; ++i) {
    const std::uint32_t k = key[i];
    const std::uint32_t drop = k == kDropped ? 1U : 0U, kept = k - drop * k;  // dropped: 0
    lo = k < lo ? k : lo;
    hi = kept > hi ? kept : hi;
    dropped += drop;
  }
  if (dropped > 0) {
    for (std::int64_t i = first; i < last; ++i) {
      if (key[i] == kDropped) part.dropped.push_back(static_cast<std::uint32_t>(i));
    }
  }
  if (dropped == last - first) {  // nothing kept
    part.lo = 0;
    part.hi = -1;
    return;
  }
  part.lo = lo;
  part.hi = hi;
}

// The counts of one part's keys in counters of type C; false when one overflows. The counters
// wrap silently; a wrap loses a multiple of 2^bits, so the counts sum to the part's kept
// particles exactly when none wrapped (one pass over the window instead of a test per particle).
template <class C>
bool KeySort::count_part(const std::vector<std::uint32_t>& keys, Part& part) {
  std::vector<C>& counters = part.count<C>();
  counters.assign(static_cast<std::size_t>(part.hi - part.lo + 1), 0);
  // raw restrict pointers: a store through an 8-bit counter may otherwise alias anything,
  // the vectors' own pointers included, which the loop would reload after every store
  C* __restrict count = counters.data();
  const std::uint32_t* __restrict key = keys.data();
  const std::int64_t lo = part.lo, last = part.last;
  for (std::int64_t i = part.first; i < last; ++i) {
    const std::uint32_t k = key[i];
    if (k != kDropped) ++count[k - lo];
  }
  std::int64_t total = 0;
  for (const C c : counters) total += c;
  return total == part.last - part.first - static_cast<std::int64_t>(part.dropped.size());
}

// total[k] = number of particles of key k (k < nkeys); each part's count of k becomes the number
// of particles of key k in the parts before it (its offset inside the key). The totals are summed
// in 32 bits per range of keys and stored as Total. False when a key holds more particles than a
// counter of type C can reach (the offsets run up to the key's total); Total is at least as wide
// as C.
template <class C, class Total>
bool KeySort::key_totals(std::size_t nkeys, Total* total) {
  static_assert(sizeof(Total) >= sizeof(C));
  constexpr std::int64_t kRange = 4096;
  const auto n = static_cast<std::int64_t>(nkeys);
  const std::int64_t ranges = (n + kRange - 1) / kRange;
  std::vector<std::uint8_t> fits(static_cast<std::size_t>(ranges), 1);
  exec::for_each(ranges, [&](std::int64_t r) {
    const std::int64_t a = r * kRange, b = std::min(n, a + kRange);
    // restrict: 8-bit counters are of a character type, which may alias the sums otherwise,
    // and the loop would reload every sum after every counter store (not vectorised)
    std::array<std::uint32_t, kRange> sums{};
    std::uint32_t* __restrict sum = sums.data();  // of keys a .. b - 1
    for (Part& part : parts_) {
      C* __restrict count = part.count<C>().data();  // from the window's first key, part.lo
      const std::int64_t first = part.lo;  // a local: a counter store may alias part.lo too
      const std::int64_t lo = std::max(a, first), hi = std::min(b - 1, part.hi);
      for (std::int64_t k = lo; k <= hi; ++k) {
        C& c = count[k - first];
        const std::uint32_t here = c;
        c = static_cast<C>(sum[k - a]);
        sum[k - a] += here;
      }
    }
    std::uint32_t top = 0;
    for (std::int64_t k = a; k < b; ++k) {
      top = std::max(top, sum[k - a]);
      total[k] = static_cast<Total>(sum[k - a]);
    }
    fits[r] = top <= std::numeric_limits<C>::max();
  });
  return std::all_of(fits.begin(), fits.end(), [](std::uint8_t f) { return f != 0; });
}

// From the key totals in starts.off (keys 0 .. nkeys, the last 0) to the starts: each run of
// 2^shift keys scans its own totals into offsets and keeps its sum, and the run sums are scanned
// into the runs' starts (in parallel over runs, then over ranges of runs). False when a run holds
// more than 65,535 particles (its offsets would not fit in 16 bits).
bool KeySort::run_scan(KeyStarts& starts, std::size_t nkeys, int parts) {
  const std::size_t runs = (nkeys >> starts.shift) + 1;
  const std::size_t width = std::size_t{1} << starts.shift;
  starts.base.resize(runs + 1);
  std::vector<std::uint8_t> fits(runs, 1);
  exec::for_each(static_cast<std::int64_t>(runs), [&](std::int64_t q) {
    const std::size_t a = static_cast<std::size_t>(q) * width;
    const std::size_t b = std::min(nkeys + 1, a + width);
    std::uint32_t s = 0;
    for (std::size_t k = a; k < b; ++k) {
      const std::uint32_t c = starts.off[k];
      starts.off[k] = static_cast<std::uint16_t>(s);
      s += c;
    }
    starts.base[static_cast<std::size_t>(q)] = s;
    fits[static_cast<std::size_t>(q)] = s <= std::numeric_limits<std::uint16_t>::max();
  });
  if (std::find(fits.begin(), fits.end(), 0) != fits.end()) return false;
  exclusive_scan(starts.base, runs, parts);
  return true;
}

// The starts of every key from the counters of type C (turned into offsets inside each key on
// the way): 16-bit offsets from 32-bit run starts while C is narrower than 32 bits and every run
// fits, else one 32-bit start per key. False when C is too narrow or a run too full.
template <class C>
bool KeySort::starts_of(std::size_t nkeys, KeyStarts& starts) {
  const int parts = static_cast<int>(parts_.size());
  if constexpr (sizeof(C) < 4) {
    starts.shift = KeyStarts::kShift;
    starts.off.resize(nkeys + 1);
    if (!key_totals<C>(nkeys, starts.off.data())) return false;
    starts.off[nkeys] = 0;
    return run_scan(starts, nkeys, parts);
  } else {
    starts.shift = 0;
    starts.base.resize(nkeys + 1);
    key_totals<C>(nkeys, starts.base.data());  // 32 bits hold any count
    exclusive_scan(starts.base, nkeys, parts);
    starts.off.assign(nkeys + 1, 0);
    return true;
  }
}

// begin[0..nkeys) from counts to starts, begin[nkeys] = total: each of `parts` key ranges sums
// its counts, the range sums are scanned, and each range scans its own keys from its offset.
void KeySort::exclusive_scan(std::vector<std::uint32_t>& begin, std::size_t nkeys, int parts) {
  const auto n = static_cast<std::int64_t>(nkeys);
  std::vector<std::uint32_t> sums(static_cast<std::size_t>(parts) + 1, 0);
  auto range = [&](std::int64_t t, std::int64_t& a, std::int64_t& b) {
    a = n * t / parts;
    b = n * (t + 1) / parts;
  };
  exec::for_each(parts, [&](std::int64_t t) {
    std::int64_t a = 0, b = 0;
    range(t, a, b);
    std::uint32_t s = 0;
    for (std::int64_t k = a; k < b; ++k) s += begin[static_cast<std::size_t>(k)];
    sums[static_cast<std::size_t>(t) + 1] = s;
  });
  for (int t = 0; t < parts; ++t) sums[t + 1] += sums[t];
  exec::for_each(parts, [&](std::int64_t t) {
    std::int64_t a = 0, b = 0;
    range(t, a, b);
    std::uint32_t s = sums[static_cast<std::size_t>(t)];
    for (std::int64_t k = a; k < b; ++k) {
      const std::uint32_t c = begin[static_cast<std::size_t>(k)];
      begin[static_cast<std::size_t>(k)] = s;
      s += c;
    }
  });
  begin[nkeys] = sums[static_cast<std::size_t>(parts)];
}

// Counts, offsets and scatter with counters of type C; false (nothing scattered) when a key is
// too full for them.
template <class C>
bool KeySort::sort_with(const std::vector<std::uint32_t>& keys, std::size_t nkeys,
                        KeyStarts& starts, std::vector<std::uint32_t>& perm) {
  const auto parts = static_cast<std::int64_t>(parts_.size());
  std::vector<std::uint8_t> fits(parts_.size(), 1);
  exec::for_each(parts, [&](std::int64_t t) { fits[t] = count_part<C>(keys, parts_[t]); });
  if (std::find(fits.begin(), fits.end(), 0) != fits.end()) return false;
  if (!starts_of<C>(nkeys, starts)) return false;
  perm.resize(starts[nkeys]);
  exec::for_each(parts, [&](std::int64_t t) {
    Part& part = parts_[t];
    C* __restrict offset = part.count<C>().data();  // restrict: as in count_part
    const std::uint32_t* __restrict key = keys.data();
    const std::uint32_t* __restrict base = starts.base.data();
    const std::uint16_t* __restrict off = starts.off.data();
    std::uint32_t* __restrict sorted = perm.data();
    const std::int64_t lo = part.lo, last = part.last;
    const int shift = starts.shift;
    for (std::int64_t i = part.first; i < last; ++i) {
      const std::uint32_t k = key[i];
      if (k == kDropped) continue;
      sorted[base[k >> shift] + off[k] + offset[k - lo]++] = static_cast<std::uint32_t>(i);
    }
  });
  return true;
}

void KeySort::sort(const std::vector<std::uint32_t>& keys, std::size_t nkeys, KeyStarts& starts,
                   std::vector<std::uint32_t>& perm, std::vector<std::uint32_t>& dropped) {
  const auto n = static_cast<std::int64_t>(keys.size());
  const int parts = std::max(1, exec::thread_count());
  parts_.resize(static_cast<std::size_t>(parts));
  for (int t = 0; t < parts; ++t) {
    parts_[t].first = n * t / parts;
    parts_[t].last = n * (t + 1) / parts;
  }
  exec::for_each(parts, [&](std::int64_t t) { window(keys, parts_[t]); });
  if (sort_with<std::uint8_t>(keys, nkeys, starts, perm)) {
    for (Part& part : parts_) part.keep_only<std::uint8_t>();
  } else if (sort_with<std::uint16_t>(keys, nkeys, starts, perm)) {
    for (Part& part : parts_) part.keep_only<std::uint16_t>();
  } else {
    sort_with<std::uint32_t>(keys, nkeys, starts, perm);  // 32 bits hold any count
    for (Part& part : parts_) part.keep_only<std::uint32_t>();
  }
  dropped.clear();
  for (const Part& part : parts_)
    dropped.insert(dropped.end(), part.dropped.begin(), part.dropped.end());
}

}  // namespace vrsph
