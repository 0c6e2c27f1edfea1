#include "vrsph/particles/key_sort.hpp"

#include <algorithm>

#include "vrsph/exec/parallel.hpp"

namespace vrsph {

// The key window of one part and its counts.
void KeySort::count_part(const std::vector<std::int64_t>& keys, Part& part) {
  part.lo = INT64_MAX;
  part.hi = -1;
  part.dropped.clear();
  for (std::int64_t i = part.first; i < part.last; ++i) {
    const std::int64_t k = keys[static_cast<std::size_t>(i)];
    if (k < 0) continue;
    part.lo = std::min(part.lo, k);
    part.hi = std::max(part.hi, k);
  }
  if (part.hi < part.lo) {
    part.lo = 0;
    part.hi = -1;
  }
  part.count.assign(static_cast<std::size_t>(part.hi - part.lo + 1), 0);
  for (std::int64_t i = part.first; i < part.last; ++i) {
    const std::int64_t k = keys[static_cast<std::size_t>(i)];
    if (k < 0) {
      part.dropped.push_back(static_cast<std::uint32_t>(i));
      continue;
    }
    ++part.count[static_cast<std::size_t>(k - part.lo)];
  }
}

// begin[k] = number of particles of key k; each part's count of k becomes the number of
// particles of key k in the parts before it (its offset inside the key).
void KeySort::key_totals(std::size_t nkeys, std::vector<std::uint32_t>& begin) {
  constexpr std::int64_t kRange = 4096;
  const auto n = static_cast<std::int64_t>(nkeys);
  const std::int64_t ranges = (n + kRange - 1) / kRange;
  exec::for_each(ranges, [&](std::int64_t r) {
    const std::int64_t a = r * kRange, b = std::min(n, a + kRange);
    std::fill(begin.begin() + a, begin.begin() + b, 0u);
    for (Part& part : parts_) {
      const std::int64_t lo = std::max(a, part.lo), hi = std::min(b - 1, part.hi);
      for (std::int64_t k = lo; k <= hi; ++k) {
        std::uint32_t& c = part.count[static_cast<std::size_t>(k - part.lo)];
        const std::uint32_t here = c;
        c = begin[static_cast<std::size_t>(k)];
        begin[static_cast<std::size_t>(k)] += here;
      }
    }
  });
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

void KeySort::sort(const std::vector<std::int64_t>& keys, std::size_t nkeys,
                   std::vector<std::uint32_t>& begin, std::vector<std::uint32_t>& perm,
                   std::vector<std::uint32_t>& dropped) {
  const auto n = static_cast<std::int64_t>(keys.size());
  const int parts = std::max(1, exec::thread_count());
  parts_.resize(static_cast<std::size_t>(parts));
  for (int t = 0; t < parts; ++t) {
    parts_[t].first = n * t / parts;
    parts_[t].last = n * (t + 1) / parts;
  }
  exec::for_each(parts, [&](std::int64_t t) { count_part(keys, parts_[t]); });
  begin.resize(nkeys + 1);
  key_totals(nkeys, begin);
  exclusive_scan(begin, nkeys, parts);
  perm.resize(begin[nkeys]);
  exec::for_each(parts, [&](std::int64_t t) {
    Part& part = parts_[t];
    for (std::int64_t i = part.first; i < part.last; ++i) {
      const std::int64_t k = keys[static_cast<std::size_t>(i)];
      if (k < 0) continue;
      std::uint32_t& off = part.count[static_cast<std::size_t>(k - part.lo)];
      perm[begin[static_cast<std::size_t>(k)] + off++] = static_cast<std::uint32_t>(i);
    }
  });
  dropped.clear();
  for (const Part& part : parts_)
    dropped.insert(dropped.end(), part.dropped.begin(), part.dropped.end());
}

}  // namespace vrsph
