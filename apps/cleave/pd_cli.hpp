// `cleave run` / `cleave check` for scenes with "method": "peridynamics" (libmpm/pd).
#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace cleave::app {

struct PdCliArgs {
  std::string command, scene, out;
  bool resume = false, quiet = false;
};

// Same exit codes as the MPM path: 0 done, 3 run stopped on a detected problem. SceneError and
// other exceptions propagate to main's handlers (exit 2 and 1).
int run_peridynamics(const nlohmann::json& scene, const PdCliArgs& a);

}  // namespace cleave::app
