// VTK XML's zlib-compressed binary data (compressor="vtkZLibDataCompressor", header_type UInt64),
// as VTK's own writer lays it out and its readers (ParaView) expect:
//   UInt64 number of blocks nb, UInt64 uncompressed block size, UInt64 uncompressed size of the
//   last block (0 when the last block is full), nb x UInt64 compressed size of each block,
//   then the nb zlib streams one after the other.
// The data is cut into blocks of kVtkBlockSize bytes (the last may be shorter), each compressed
// on its own (zlib format, RFC 1950).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace vrsph {

inline constexpr std::size_t kVtkBlockSize = 32768;  // bytes, VTK's default

// The compressed form of `raw`, header included. Throws std::runtime_error when zlib fails.
std::string vtk_zlib_compress(std::string_view raw, std::size_t block_size = kVtkBlockSize);

}  // namespace vrsph
