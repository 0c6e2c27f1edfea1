// VTK XML zlib-compressed data blocks (see vtk_zlib.hpp).
#include "vrsph/output/vtk_zlib.hpp"

#include <fmt/format.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace vrsph {

std::string vtk_zlib_compress(std::string_view raw, std::size_t block_size) {
  const std::size_t n_blocks = (raw.size() + block_size - 1) / block_size;
  std::vector<std::uint64_t> header{n_blocks, block_size, raw.size() % block_size};
  std::string blocks;
  std::vector<unsigned char> buf(compressBound(static_cast<uLong>(block_size)));
  for (std::size_t b = 0; b < n_blocks; ++b) {
    const std::string_view in = raw.substr(b * block_size, block_size);
    uLongf out_size = static_cast<uLongf>(buf.size());
    const int rc = compress2(buf.data(), &out_size, reinterpret_cast<const Bytef*>(in.data()),
                             static_cast<uLong>(in.size()), Z_DEFAULT_COMPRESSION);
    if (rc != Z_OK) throw std::runtime_error(fmt::format("zlib compress2 failed ({})", rc));
    header.push_back(out_size);
    blocks.append(reinterpret_cast<const char*>(buf.data()), out_size);
  }
  std::string out(header.size() * sizeof(std::uint64_t), '\0');
  std::memcpy(out.data(), header.data(), out.size());
  return out + blocks;
}

}  // namespace vrsph
