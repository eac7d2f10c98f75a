#include "libmpm/io/output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <stdexcept>

#include "libmpm/core/error.hpp"

namespace cleave::io {

OutputLock::OutputLock(const std::filesystem::path& dir, const std::string& holder) {
  const std::filesystem::path file = dir / "run.lock";
  fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error(file.string() + ": cannot open the lock file: " + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    // The holder wrote who it is right after locking; an empty read means it is just starting.
    char buf[512] = {};
    const ssize_t n = ::pread(fd_, buf, sizeof buf - 1, 0);
    std::string who(buf, n > 0 ? std::size_t(n) : 0);
    while (!who.empty() && (who.back() == '\n' || who.back() == ' ')) who.pop_back();
    ::close(fd_);
    fd_ = -1;
    if (err != EWOULDBLOCK)
      throw std::runtime_error(file.string() + ": cannot lock the output directory: " + std::strerror(err));
    const std::string pid = who.rfind("pid ", 0) == 0 ? who.substr(4, who.find_first_not_of("0123456789", 4) - 4) : "";
    throw RunRefused(dir.string() + " is in use by another cleave run (" + (who.empty() ? "pid unknown" : who) +
                     "); wait for it to end, stop it (kill -TERM " + (pid.empty() ? "PID" : pid) +
                     ", it checkpoints and can be resumed), or choose another --out");
  }
  // Who holds it, for a refused second run to name. A failure here costs only that message.
  if (::ftruncate(fd_, 0) == 0) {
    const std::string text = holder + "\n";
    [[maybe_unused]] const ssize_t n = ::pwrite(fd_, text.data(), text.size(), 0);
  }
}

OutputLock::~OutputLock() {
  if (fd_ >= 0) ::close(fd_);  // closing the only descriptor releases the flock
}

std::string describe_this_process() {
  char when[32] = "?";
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  if (localtime_r(&now, &tm)) std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S", &tm);
  return "pid " + std::to_string(::getpid()) + ", started " + when;
}

}  // namespace cleave::io
