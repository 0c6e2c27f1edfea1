// Stable counting sort of particle indices by an integer key, in parallel with no serial phase
// over the particles or the keys, and the same permutation for any thread count.
//
// The particles are split into P consecutive parts (one per thread). Each part counts its keys
// over the key window it actually holds: particles are sorted by cell already from the previous
// step, so a part's window is a narrow slice of the key range and the counters of all parts
// together take about one entry per key, not P. Then, key by key (in parallel over key ranges),
// each part's count becomes its offset inside the key (parts in order: stability), the key
// totals are scanned into the start of every key (in parallel, by ranges), and each part
// scatters its particles to start + offset. Particles with key -1 are dropped and reported in
// order. This is the scheme of a parallel radix-sort pass (Satish et al. 2009; Zagha & Blelloch
// 1991) with windows in place of full per-thread histograms.
#pragma once

#include <cstdint>
#include <vector>

namespace vrsph {

class KeySort {
 public:
  // keys[i] in [0, nkeys) or -1 (dropped). On return begin has nkeys + 1 entries, begin[k] ..
  // begin[k + 1] being the sorted positions of key k; perm[s] is the index of the particle at
  // sorted position s; dropped lists the indices with key -1 in increasing order.
  void sort(const std::vector<std::int64_t>& keys, std::size_t nkeys,
            std::vector<std::uint32_t>& begin, std::vector<std::uint32_t>& perm,
            std::vector<std::uint32_t>& dropped);

 private:
  // Counters are 16 bits wide while no key holds more than 65,535 particles (cells hold a few:
  // half the memory of the counters, which are as long as the cell table); a sort that finds a
  // fuller key counts again in 32 bits. The result is the same either way.
  struct Part {
    std::int64_t first = 0, last = 0;  // particle range [first, last)
    std::int64_t lo = 0, hi = -1;      // key window [lo, hi]; empty when hi < lo
    // per key of the window: count, then offset in the key (one of the two, by width)
    std::vector<std::uint16_t> count16;
    std::vector<std::uint32_t> count32;
    std::vector<std::uint32_t> dropped;
    template <class C>
    std::vector<C>& count() {
      if constexpr (sizeof(C) == 2)
        return count16;
      else
        return count32;
    }
  };
  template <class C>
  bool sort_with(const std::vector<std::int64_t>& keys, std::size_t nkeys,
                 std::vector<std::uint32_t>& begin, std::vector<std::uint32_t>& perm);
  void window(const std::vector<std::int64_t>& keys, Part& part);
  template <class C>
  bool count_part(const std::vector<std::int64_t>& keys, Part& part);
  template <class C>
  bool key_totals(std::size_t nkeys, std::vector<std::uint32_t>& begin);
  static void exclusive_scan(std::vector<std::uint32_t>& begin, std::size_t nkeys, int parts);

  std::vector<Part> parts_;
};

}  // namespace vrsph
