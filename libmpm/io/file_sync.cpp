#include "libmpm/io/file_sync.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>

namespace cleave::io {

int sync_descriptor(int fd) {
  while (::fsync(fd) != 0) {
    if (errno == EINTR) continue;
    return errno == EINVAL || errno == ENOTSUP ? 0 : errno;
  }
  return 0;
}

int sync_file(const std::filesystem::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return errno;
  const int err = sync_descriptor(fd);
  ::close(fd);
  return err;
}

void sync_directory(const std::filesystem::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  (void)sync_descriptor(fd);
  ::close(fd);
}

}  // namespace cleave::io
