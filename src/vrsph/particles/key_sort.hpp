// Stable counting sort of particle indices by an integer key, in parallel with no serial phase
// over the particles or the keys, and the same permutation for any thread count.
//
// The particles are split into P consecutive parts (one per thread). Each part counts its keys
// over the key window it actually holds: particles are sorted by cell already from the previous
// step, so a part's window is a narrow slice of the key range and the counters of all parts
// together take about one entry per key, not P. Then, key by key (in parallel over key ranges),
// each part's count becomes its offset inside the key (parts in order: stability), the key
// totals are scanned into the start of every key (in parallel, by ranges), and each part
// scatters its particles to start + offset. Particles with key kDropped are dropped and reported
// in order. This is the scheme of a parallel radix-sort pass (Satish et al. 2009; Zagha & Blelloch
// 1991) with windows in place of full per-thread histograms.
#pragma once

#include <cstdint>
#include <vector>

namespace vrsph {

// Where the particles of each key start after a sort, in about 2 bytes per key: a 32-bit start
// per run of 2^shift keys and a 16-bit offset from it per key. A sort whose runs hold more than
// 65,535 particles (or one key more than 65,535) takes one 32-bit start per key instead (shift
// 0, offsets 0): the same starts, in 6 bytes per key.
struct KeyStarts {
  static constexpr int kShift = 6;  // runs of 64 keys: a few hundred particles at most
  int shift = kShift;
  std::vector<std::uint32_t> base;  // start of each run, then the total
  std::vector<std::uint16_t> off;   // per key, and one past the last key
  std::uint32_t operator[](std::size_t k) const { return base[k >> shift] + off[k]; }
};

class KeySort {
 public:
  // The key of a particle to drop; every other key is below nkeys, so nkeys < kDropped.
  static constexpr std::uint32_t kDropped = 0xFFFFFFFFu;

  // keys[i] in [0, nkeys) or kDropped. On return starts[k] .. starts[k + 1] are the sorted
  // positions of key k (k < nkeys); perm[s] is the index of the particle at sorted position s;
  // dropped lists the indices with key kDropped in increasing order.
  void sort(const std::vector<std::uint32_t>& keys, std::size_t nkeys, KeyStarts& starts,
            std::vector<std::uint32_t>& perm, std::vector<std::uint32_t>& dropped);

 private:
  // Counters are as narrow as the fullest key allows: 8 bits while no key holds more than 255
  // particles (cells hold a few), else 16 bits up to 65,535, else 32. They are as long as the
  // cell table, so their width is a quarter of the table's memory. A sort that finds a key too
  // full for one width counts again with the next; the result is the same either way.
  struct Part {
    std::int64_t first = 0, last = 0;  // particle range [first, last)
    std::int64_t lo = 0, hi = -1;      // key window [lo, hi]; empty when hi < lo
    // per key of the window: count, then offset in the key (one of the three, by width)
    std::vector<std::uint8_t> count8;
    std::vector<std::uint16_t> count16;
    std::vector<std::uint32_t> count32;
    std::vector<std::uint32_t> dropped;
    template <class C>
    std::vector<C>& count() {
      if constexpr (sizeof(C) == 1)
        return count8;
      else if constexpr (sizeof(C) == 2)
        return count16;
      else
        return count32;
    }
    // Gives back the counters of every width but C's.
    template <class C>
    void keep_only();
  };
  template <class C>
  bool sort_with(const std::vector<std::uint32_t>& keys, std::size_t nkeys, KeyStarts& starts,
                 std::vector<std::uint32_t>& perm);
  template <class C>
  bool starts_of(std::size_t nkeys, KeyStarts& starts);
  void window(const std::vector<std::uint32_t>& keys, Part& part);
  template <class C>
  bool count_part(const std::vector<std::uint32_t>& keys, Part& part);
  template <class C, class Total>
  bool key_totals(std::size_t nkeys, Total* total);
  static void exclusive_scan(std::vector<std::uint32_t>& begin, std::size_t nkeys, int parts);
  static bool run_scan(KeyStarts& starts, std::size_t nkeys, int parts);

  std::vector<Part> parts_;
};

}  // namespace vrsph
