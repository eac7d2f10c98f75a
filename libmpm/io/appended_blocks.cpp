// Compression level 1 (zlib's fastest): on a frame of the default scene it deflates almost as far
// as VTK's default level 5 at a fraction of the time (docs/performance.md, "Output formats").
#include "libmpm/io/appended_blocks.hpp"

#include <zlib.h>

#include <stdexcept>
#include <string>

namespace cleave::io {

namespace {

constexpr int kZlibLevel = 1;

struct Task {
  std::size_t array;
  std::span<const char> in;
  std::vector<char> out;
  int status = Z_OK;
};

}  // namespace

std::vector<AppendedBlock> encode_appended(const std::vector<std::span<const char>>& arrays, bool zlib) {
  std::vector<AppendedBlock> blocks(arrays.size());
  if (!zlib) {
    for (std::size_t a = 0; a < arrays.size(); ++a) {
      blocks[a].header = {arrays[a].size()};
      blocks[a].payload = arrays[a];
    }
    return blocks;
  }
  std::vector<Task> tasks;
  for (std::size_t a = 0; a < arrays.size(); ++a)
    for (std::size_t at = 0; at < arrays[a].size(); at += kZlibBlockBytes)
      tasks.push_back({a, arrays[a].subspan(at, std::min(kZlibBlockBytes, arrays[a].size() - at)), {}});
  const long n = static_cast<long>(tasks.size());
#pragma omp parallel for schedule(dynamic) if (n > 1)
  for (long k = 0; k < n; ++k) {
    Task& t = tasks[static_cast<std::size_t>(k)];
    uLongf len = compressBound(static_cast<uLong>(t.in.size()));
    t.out.resize(len);
    t.status = compress2(reinterpret_cast<Bytef*>(t.out.data()), &len, reinterpret_cast<const Bytef*>(t.in.data()),
                         static_cast<uLong>(t.in.size()), kZlibLevel);
    t.out.resize(len);
  }
  for (std::size_t a = 0; a < arrays.size(); ++a) {
    const std::size_t bytes = arrays[a].size();
    const std::size_t count = (bytes + kZlibBlockBytes - 1) / kZlibBlockBytes;
    blocks[a].header = {count, kZlibBlockBytes, bytes % kZlibBlockBytes};
  }
  for (const Task& t : tasks) {
    if (t.status != Z_OK) throw std::runtime_error("zlib compress2 failed (status " + std::to_string(t.status) + ")");
    AppendedBlock& b = blocks[t.array];
    b.header.push_back(t.out.size());
    b.owned.insert(b.owned.end(), t.out.begin(), t.out.end());
  }
  for (auto& b : blocks) b.payload = b.owned;
  return blocks;
}

}  // namespace cleave::io
