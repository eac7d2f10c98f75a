#include "libmpm/io/checkpoint.hpp"

#include <fstream>
#include <stdexcept>

namespace cleave::io {
namespace {

constexpr uint64_t kMagic = 0x33504B4345564C43ull;  // "CLVECKP3" (with rotation and cracks)

template <class T>
void put(std::ofstream& o, const std::vector<T>& v) {
  o.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
}
template <class T>
void get(std::ifstream& i, std::vector<T>& v, const std::filesystem::path& f) {
  i.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
  if (!i) throw std::runtime_error(f.string() + ": checkpoint is truncated");
}

}  // namespace

template <int Dim>
void write_checkpoint(const std::filesystem::path& file, const Model<Dim>& m, const CheckpointInfo& info) {
  const auto tmp = file.string() + ".tmp";
  {
    std::ofstream o(tmp, std::ios::binary | std::ios::trunc);
    if (!o) throw std::runtime_error(tmp + ": cannot write checkpoint");
    const uint64_t header[3] = {kMagic, static_cast<uint64_t>(Dim), static_cast<uint64_t>(m.particles.size())};
    o.write(reinterpret_cast<const char*>(header), sizeof(header));
    o.write(reinterpret_cast<const char*>(&info), sizeof(info));
    const auto& P = m.particles;
    put(o, P.x), put(o, P.v), put(o, P.u), put(o, P.stress), put(o, P.strain), put(o, P.rotation);
    for (const auto& c : m.cracks) put(o, c.points), put(o, c.above), put(o, c.below);
    if (!o) throw std::runtime_error(tmp + ": error while writing checkpoint");
  }
  std::filesystem::rename(tmp, file);
}

template <int Dim>
CheckpointInfo read_checkpoint(const std::filesystem::path& file, Model<Dim>& m) {
  std::ifstream i(file, std::ios::binary);
  if (!i) throw std::runtime_error(file.string() + ": no checkpoint to resume from");
  uint64_t header[3];
  CheckpointInfo info;
  i.read(reinterpret_cast<char*>(header), sizeof(header));
  i.read(reinterpret_cast<char*>(&info), sizeof(info));
  if (!i || header[0] != kMagic) throw std::runtime_error(file.string() + ": not a Cleave checkpoint");
  if (header[1] != static_cast<uint64_t>(Dim) || header[2] != m.particles.size())
    throw std::runtime_error(file.string() + ": checkpoint holds " + std::to_string(header[2]) + " particles in " +
                             std::to_string(header[1]) + "D; the scene builds " +
                             std::to_string(m.particles.size()) + " in " + std::to_string(Dim) + "D");
  auto& P = m.particles;
  get(i, P.x, file), get(i, P.v, file), get(i, P.u, file), get(i, P.stress, file), get(i, P.strain, file);
  get(i, P.rotation, file);
  for (auto& c : m.cracks) {
    get(i, c.points, file), get(i, c.above, file), get(i, c.below, file);
    c.update_extent();
  }
  return info;
}

template void write_checkpoint<2>(const std::filesystem::path&, const Model<2>&, const CheckpointInfo&);
template void write_checkpoint<3>(const std::filesystem::path&, const Model<3>&, const CheckpointInfo&);
template CheckpointInfo read_checkpoint<2>(const std::filesystem::path&, Model<2>&);
template CheckpointInfo read_checkpoint<3>(const std::filesystem::path&, Model<3>&);

}  // namespace cleave::io
