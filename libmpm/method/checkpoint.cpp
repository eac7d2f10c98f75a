#include "libmpm/method/checkpoint.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>

#include "libmpm/core/error.hpp"
#include "libmpm/io/file_sync.hpp"
#include "libmpm/method/state_io.hpp"

namespace cleave {
namespace fs = std::filesystem;

namespace {
// Format 4 is the first shared by every method (formats 1-3 were per method); 5 adds the crack-tip
// table's last records (method/tip_table.hpp) to every method's state.
constexpr char kMagic[8] = {'C', 'L', 'V', 'E', 'C', 'K', 'P', '6'};
}  // namespace

template <int Dim>
void write_checkpoint(const fs::path& file, const Method<Dim>& method, const LoopCounters& c) {
  const std::string tmp = file.string() + ".tmp";
  int err = 0;
  {
    std::ofstream o(tmp, std::ios::binary | std::ios::trunc);
    if (!o) throw std::runtime_error("cannot write " + tmp + ": " + std::strerror(errno));
    o.write(kMagic, sizeof kMagic);
    char name[24] = {};
    std::strncpy(name, method.name(), sizeof name - 1);
    o.write(name, sizeof name);
    StateWriter w(o);
    w.value(uint32_t(Dim));
    w.value(c);
    method.save(w);
    // The stream stops writing at its first failed write(2), so errno still holds that one's cause.
    o.flush();
    if (!o) err = errno;
    o.close();
    if (!err && o.fail()) err = errno;
  }
  if (err) {
    ::unlink(tmp.c_str());
    throw std::runtime_error("cannot write " + file.string() + ": " + std::strerror(err));
  }
  // On the disk before it replaces the last checkpoint: after a power cut, the old one or the new.
  if ((err = io::sync_file(tmp)) != 0) {
    ::unlink(tmp.c_str());
    throw std::runtime_error("cannot write " + file.string() + ": fsync: " + std::strerror(err));
  }
  if (::rename(tmp.c_str(), file.c_str()) != 0) {
    err = errno;
    ::unlink(tmp.c_str());
    throw std::runtime_error("cannot write " + file.string() + ": rename: " + std::strerror(err));
  }
  io::sync_directory(file.parent_path());  // the new name too
}

template <int Dim>
LoopCounters read_checkpoint(const fs::path& file, Method<Dim>& method, uint64_t scene_hash) {
  const std::string f = file.string();
  std::ifstream i(file, std::ios::binary);
  if (!i) throw RunRefused(f + ": no checkpoint to resume from");
  char magic[8] = {}, name[24] = {};
  i.read(magic, sizeof magic);
  if (!i || std::memcmp(magic, kMagic, 7) != 0) throw RunRefused(f + ": not a Cleave checkpoint");
  if (magic[7] != kMagic[7])
    throw RunRefused(f + ": written by an earlier Cleave (checkpoint format " + std::string(1, magic[7]) +
                     "; this version reads format " + std::string(1, kMagic[7]) + "); run without --resume");
  i.read(name, sizeof name);
  name[sizeof name - 1] = 0;
  try {
    StateReader r(i, f);
    uint32_t dim = 0;
    r.value(dim);
    if (std::string(name) != method.name() || dim != uint32_t(Dim))
      throw RunRefused(f + ": the checkpoint is of a " + std::to_string(dim) + "D " + name + " run; the scene is a " +
                       std::to_string(Dim) + "D " + method.name() + " scene (run without --resume)");
    LoopCounters c;
    r.value(c);
    if (c.scene_hash != scene_hash) throw RunRefused(f + ": written for a different scene; run without --resume");
    method.load(r);
    return c;
  } catch (const RunRefused&) {
    throw;
  } catch (const std::runtime_error& e) {  // StateReader: truncated, or arrays of another size
    throw RunRefused(e.what());
  }
}

template void write_checkpoint<2>(const fs::path&, const Method<2>&, const LoopCounters&);
template void write_checkpoint<3>(const fs::path&, const Method<3>&, const LoopCounters&);
template LoopCounters read_checkpoint<2>(const fs::path&, Method<2>&, uint64_t);
template LoopCounters read_checkpoint<3>(const fs::path&, Method<3>&, uint64_t);

}  // namespace cleave
