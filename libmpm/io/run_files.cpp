#include "libmpm/io/run_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "libmpm/io/file_sync.hpp"

namespace cleave::io {
namespace fs = std::filesystem;

namespace {

std::string run_json_text(const std::string& status, const std::string& message, long step, double time,
                          const nlohmann::json& extra) {
  nlohmann::json j = {{"status", status}, {"message", message}, {"step", step}, {"time", time}};
  for (auto it = extra.begin(); it != extra.end(); ++it) j[it.key()] = it.value();
  return j.dump(2) + "\n";
}

// Writes all of `text` to `fd` from offset 0; false with errno set on failure.
bool write_all(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::pwrite(fd, text.data() + done, text.size() - done, off_t(done));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += std::size_t(n);
  }
  return true;
}

// POSIX calls rather than a stream: the error is errno's, named as the user needs it.
void write_atomically(const fs::path& file, const std::string& text) {
  const fs::path tmp = file.string() + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error("cannot write " + tmp.string() + ": " + std::strerror(errno));
  const bool ok = write_all(fd, text);
  const int err = errno;
  // On the disk before the rename (io/file_sync.hpp): a power cut leaves the old file or the new.
  const int sync_err = ok ? sync_descriptor(fd) : 0;
  if (::close(fd) != 0 || !ok || sync_err) {
    const int e = !ok ? err : sync_err ? sync_err : errno;
    ::unlink(tmp.c_str());
    throw std::runtime_error("cannot write " + file.string() + (sync_err ? ": fsync: " : ": ") + std::strerror(e));
  }
  if (::rename(tmp.c_str(), file.c_str()) != 0) {
    const int e = errno;
    ::unlink(tmp.c_str());
    throw std::runtime_error("cannot write " + file.string() + ": rename: " + std::strerror(e));
  }
}

}  // namespace

void write_run_status(const fs::path& out, const std::string& status, const std::string& message, long step,
                      double time, const nlohmann::json& extra) {
  write_atomically(out / "run.json", run_json_text(status, message, step, time, extra));
}

std::string write_final_run_status(const fs::path& out, const std::string& status, const std::string& message,
                                   long step, double time, const nlohmann::json& extra) {
  std::string text;
  try {
    text = run_json_text(status, message, step, time, extra);
    write_atomically(out / "run.json", text);
    return "";
  } catch (const std::exception& e) {
    if (text.empty()) return e.what();
    const fs::path file = out / "run.json";
    const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
    const bool ok = fd >= 0 && write_all(fd, text) && ::ftruncate(fd, off_t(text.size())) == 0;
    const int err = errno;
    if (fd >= 0) ::close(fd);
    return ok ? "" : std::string(e.what()) + "; in place: " + std::strerror(err);
  }
}

std::string frame_file_name(const std::string& series, int k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "_%06d.vtu", k);
  return series + buf;
}

void remove_run_outputs(const fs::path& out, const std::vector<std::string>& series,
                        const std::vector<std::string>& files) {
  std::vector<fs::path> doomed;
  for (const auto& e : fs::directory_iterator(out)) {
    const std::string n = e.path().filename().string();
    bool remove = std::find(files.begin(), files.end(), n) != files.end();
    for (const auto& s : series)
      remove = remove || n == s + ".pvd" || (n.rfind(s + "_", 0) == 0 && e.path().extension() == ".vtu");
    if (remove) doomed.push_back(e.path());
  }
  for (const auto& p : doomed) fs::remove(p);
}

void remove_temporaries(const fs::path& out, const std::vector<std::string>& series,
                        const std::vector<std::string>& files) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(out, ec)) {
    const std::string n = e.path().filename().string();
    if (n.size() <= 4 || n.compare(n.size() - 4, 4, ".tmp") != 0) continue;
    const std::string base = n.substr(0, n.size() - 4);
    bool ours = std::find(files.begin(), files.end(), base) != files.end();
    for (const auto& s : series)
      ours = ours || base == s + ".pvd" || (base.rfind(s + "_", 0) == 0 && fs::path(base).extension() == ".vtu");
    if (ours) fs::remove(e.path(), ec);
  }
}

PvdIndex resumed_series(const fs::path& pvd_file, double checkpoint_time) {
  PvdIndex pvd = PvdIndex::load(pvd_file);
  pvd.truncate_after(checkpoint_time);
  return pvd;
}

}  // namespace cleave::io
