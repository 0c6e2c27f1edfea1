#include "vrsph/particles/key_sort.hpp"

#include <algorithm>
#include <limits>

#include "vrsph/exec/parallel.hpp"

namespace vrsph {

template <class C>
void KeySort::Part::keep_only() {
  if constexpr (sizeof(C) != 1) std::vector<std::uint8_t>().swap(count8);
  if constexpr (sizeof(C) != 2) std::vector<std::uint16_t>().swap(count16);
  if constexpr (sizeof(C) != 4) std::vector<std::uint32_t>().swap(count32);
}

// The key window of one part and its dropped particles.
void KeySort::window(const std::vector<std::uint32_t>& keys, Part& part) {
  part.lo = INT64_MAX;
  part.hi = -1;
  part.dropped.clear();
  for (std::int64_t i = part.first; i < part.last; ++i) {
    const std::uint32_t k = keys[static_cast<std::size_t>(i)];
    if (k == kDropped) {
      part.dropped.push_back(static_cast<std::uint32_t>(i));
      continue;
    }
    part.lo = std::min<std::int64_t>(part.lo, k);
    part.hi = std::max<std::int64_t>(part.hi, k);
  }
  if (part.hi < part.lo) {
    part.lo = 0;
    part.hi = -1;
  }
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

// begin[k] = number of particles of key k; each part's count of k becomes the number of
// particles of key k in the parts before it (its offset inside the key). False when a key holds
// more particles than a counter of type C can reach (the offsets run up to the key's total).
template <class C>
bool KeySort::key_totals(std::size_t nkeys, std::vector<std::uint32_t>& begin) {
  constexpr std::int64_t kRange = 4096;
  const auto n = static_cast<std::int64_t>(nkeys);
  const std::int64_t ranges = (n + kRange - 1) / kRange;
  std::vector<std::uint8_t> fits(static_cast<std::size_t>(ranges), 1);
  exec::for_each(ranges, [&](std::int64_t r) {
    const std::int64_t a = r * kRange, b = std::min(n, a + kRange);
    std::fill(begin.begin() + a, begin.begin() + b, 0u);
    // restrict: 8-bit counters are of a character type, which may alias the totals otherwise,
    // and the loop would reload every total after every counter store (not vectorised)
    std::uint32_t* __restrict total = begin.data();
    for (Part& part : parts_) {
      C* __restrict count = part.count<C>().data();  // from the window's first key, part.lo
      const std::int64_t first = part.lo;  // a local: a counter store may alias part.lo too
      const std::int64_t lo = std::max(a, first), hi = std::min(b - 1, part.hi);
      for (std::int64_t k = lo; k <= hi; ++k) {
        C& c = count[k - first];
        const std::uint32_t here = c;
        c = static_cast<C>(total[k]);
        total[k] += here;
      }
    }
    std::uint32_t top = 0;
    for (std::int64_t k = a; k < b; ++k) top = std::max(top, total[k]);
    fits[r] = top <= std::numeric_limits<C>::max();
  });
  return std::all_of(fits.begin(), fits.end(), [](std::uint8_t f) { return f != 0; });
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
                        std::vector<std::uint32_t>& begin, std::vector<std::uint32_t>& perm) {
  const auto parts = static_cast<std::int64_t>(parts_.size());
  std::vector<std::uint8_t> fits(parts_.size(), 1);
  exec::for_each(parts, [&](std::int64_t t) { fits[t] = count_part<C>(keys, parts_[t]); });
  if (std::find(fits.begin(), fits.end(), 0) != fits.end()) return false;
  if (!key_totals<C>(nkeys, begin)) return false;
  exclusive_scan(begin, nkeys, static_cast<int>(parts));
  perm.resize(begin[nkeys]);
  exec::for_each(parts, [&](std::int64_t t) {
    Part& part = parts_[t];
    C* __restrict offset = part.count<C>().data();  // restrict: as in count_part
    const std::uint32_t* __restrict key = keys.data();
    const std::uint32_t* __restrict start = begin.data();
    std::uint32_t* __restrict sorted = perm.data();
    const std::int64_t lo = part.lo, last = part.last;
    for (std::int64_t i = part.first; i < last; ++i) {
      const std::uint32_t k = key[i];
      if (k == kDropped) continue;
      sorted[start[k] + offset[k - lo]++] = static_cast<std::uint32_t>(i);
    }
  });
  return true;
}

void KeySort::sort(const std::vector<std::uint32_t>& keys, std::size_t nkeys,
                   std::vector<std::uint32_t>& begin, std::vector<std::uint32_t>& perm,
                   std::vector<std::uint32_t>& dropped) {
  const auto n = static_cast<std::int64_t>(keys.size());
  const int parts = std::max(1, exec::thread_count());
  parts_.resize(static_cast<std::size_t>(parts));
  for (int t = 0; t < parts; ++t) {
    parts_[t].first = n * t / parts;
    parts_[t].last = n * (t + 1) / parts;
  }
  exec::for_each(parts, [&](std::int64_t t) { window(keys, parts_[t]); });
  begin.resize(nkeys + 1);
  if (sort_with<std::uint8_t>(keys, nkeys, begin, perm)) {
    for (Part& part : parts_) part.keep_only<std::uint8_t>();
  } else if (sort_with<std::uint16_t>(keys, nkeys, begin, perm)) {
    for (Part& part : parts_) part.keep_only<std::uint16_t>();
  } else {
    sort_with<std::uint32_t>(keys, nkeys, begin, perm);  // 32 bits hold any count
    for (Part& part : parts_) part.keep_only<std::uint32_t>();
  }
  dropped.clear();
  for (const Part& part : parts_)
    dropped.insert(dropped.end(), part.dropped.begin(), part.dropped.end());
}

}  // namespace vrsph
