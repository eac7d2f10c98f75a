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

}  // namespace cleave
