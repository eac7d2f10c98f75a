// The library's entry point for running a scene: the scene JSON (with `--set`-style overrides) ->
// the registered method named by its "method" key, in its dimension -> the one run loop. The CLI,
// a study driver and the tests use it; none of them needs to know which method or dimension.
#pragma once
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "libmpm/method/method.hpp"
#include "libmpm/method/run_estimate.hpp"
#include "libmpm/method/run_loop.hpp"

namespace cleave {

// A built scene: its method in its dimension, behind one handle.
class SceneMethod {
 public:
  // Validates the scene and builds its method (SceneError names the key otherwise).
  static SceneMethod build(const nlohmann::json& scene);

  int dimension() const { return m2_ ? 2 : 3; }
  const char* name() const;
  const RunSettings& settings() const;
  std::vector<std::string> describe() const;
  std::pair<double, std::string> work_per_step() const;
  // The tables the run writes and their columns: global.csv always, the tip file (crack_tips.csv,
  // 3D fronts crack_fronts.csv) when the scene asks for tip output.
  std::vector<std::pair<std::string, std::vector<std::string>>> tables() const;
  // Points, steps, memory and output of the run (method/run_estimate.hpp).
  RunEstimate estimate();
  // Runs with the one run loop; opt.scene_hash is set to the scene's. First refuses (SceneError,
  // nothing written) a run whose output would not fit on opt.out's disk, unless --force.
  RunSummary run(RunOptions opt);

 private:
  std::unique_ptr<Method<2>> m2_;
  std::unique_ptr<Method<3>> m3_;
  uint64_t hash_ = 0;
};

// Applies the overrides (KEY=VALUE, scene/scene.hpp: each key once), builds the scene's method and runs it.
RunSummary run_scene(nlohmann::json scene, const std::vector<std::string>& overrides, const RunOptions& opt);

}  // namespace cleave
