// The blocks of a VTK XML file's <AppendedData> (header_type="UInt64"), raw or compressed exactly
// as VTK's own writer compresses them (vtkZLibDataCompressor), so VTK, ParaView and meshio read them.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace cleave::io {

// One DataArray's block: its header words, then its payload.
//   raw:  header {bytes}; payload = the caller's bytes (not copied)
//   zlib: header {blocks, block size, size of a partial last block (0 when it is full),
//         compressed size of each block}; payload = the deflated blocks, one after another
struct AppendedBlock {
  std::vector<std::uint64_t> header;
  std::span<const char> payload;
  std::vector<char> owned;  // zlib: the deflated bytes `payload` points into
  std::uint64_t size() const { return header.size() * sizeof(std::uint64_t) + payload.size(); }
};

// VTK's default block size: 32 KiB of uncompressed data per deflate call.
inline constexpr std::size_t kZlibBlockBytes = 32768;

// Encodes each array. zlib compresses the blocks of all arrays in parallel (OpenMP; every block is
// deflated on its own, so the bytes do not depend on the thread count). Throws std::runtime_error
// if zlib fails.
std::vector<AppendedBlock> encode_appended(const std::vector<std::span<const char>>& arrays, bool zlib);

}  // namespace cleave::io
