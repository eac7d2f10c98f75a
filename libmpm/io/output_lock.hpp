// One run at a time in an output directory: an exclusive flock on DIR/run.lock, held for the
// run's lifetime. The kernel drops it when the process ends however it ends (a SIGKILLed run never
// blocks the next --resume), so there is no stale-lock clean-up. The file stays in place (removing
// it would let two runs lock two different inodes) and holds the holder's pid, start time and
// command line, which a refused run prints.
#pragma once
#include <filesystem>
#include <string>

namespace cleave::io {

class OutputLock {
 public:
  // Locks `dir`/run.lock (created if missing) and writes `holder` ("pid 123, started ...") into
  // it. Throws RunRefused naming the directory and the running holder when another process holds
  // it, std::runtime_error when the file cannot be opened.
  OutputLock(const std::filesystem::path& dir, const std::string& holder);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  int fd_ = -1;
};

// "pid 1234, started 2025-06-01 14:03:12": this process, now.
std::string describe_this_process();

}  // namespace cleave::io
