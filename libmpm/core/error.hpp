// Errors that reach the user. A SceneError names the scene key path (e.g. "bodies[1].material")
// and the reason, so `cleave check` and `cleave run` can print one precise line and exit 2.
#pragma once
#include <stdexcept>
#include <string>

namespace cleave {

class SceneError : public std::runtime_error {
 public:
  SceneError(std::string key_path, std::string reason)
      : std::runtime_error(key_path + ": " + reason), key_path_(std::move(key_path)),
        reason_(std::move(reason)) {}
  const std::string& key_path() const { return key_path_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string key_path_;
  std::string reason_;
};

// A run that had to stop (particle left the grid, NaN, energy blow-up); the message names step,
// time, particle and position. The last state has been written when this is thrown.
class RunAborted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A run that stopped because an output could not be written (disk full, file size limit): the
// message names the file and the cause. Nothing of the state at the failure is written; the last
// complete frame and checkpoint are kept, so the run can be resumed once there is room.
class RunOutputFailed : public RunAborted {
 public:
  using RunAborted::RunAborted;
};

// A run that cannot start in its output directory: the checkpoint to resume from is missing, of
// another scene, method, dimension or format, or another run holds the directory. Nothing was
// written; the CLI exits 2 as for a bad scene.
class RunRefused : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A run stopped on request (SIGINT, SIGTERM) after finishing its step and writing a checkpoint
// there; run.json says "stopped" and how to resume.
class RunStopped : public std::runtime_error {
 public:
  RunStopped(int signal, const std::string& message) : std::runtime_error(message), signal_(signal) {}
  int signal() const { return signal_; }

 private:
  int signal_;
};

}  // namespace cleave
