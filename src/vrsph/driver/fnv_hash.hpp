// FNV-1a, 64 bits (Fowler, Noll and Vo; offset basis 14695981039346656037, prime 1099511628211):
// h = (h xor byte) * prime over the bytes in order. Used for the checksum of each checkpoint
// record and the hash of a checkpointed case. Not cryptographic: it finds damage, not tampering.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace vrsph {

class Fnv1a64 {
 public:
  static constexpr std::uint64_t kOffsetBasis = 14695981039346656037ull;
  static constexpr std::uint64_t kPrime = 1099511628211ull;

  Fnv1a64& add(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    std::uint64_t h = h_;
    for (std::size_t k = 0; k < n; ++k) h = (h ^ p[k]) * kPrime;
    h_ = h;
    return *this;
  }
  Fnv1a64& add(std::string_view s) { return add(s.data(), s.size()); }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = kOffsetBasis;
};

inline std::uint64_t fnv1a64(std::string_view s) { return Fnv1a64().add(s).value(); }

}  // namespace vrsph
