// What every scene sets for its run, whatever the method: read by the shared scene sections
// (scene/sections.hpp) and held by each method's model, so the one run loop (method/run_loop.hpp)
// needs nothing else from the scene.
#pragma once
#include <set>
#include <string>
#include <vector>

namespace cleave {

struct OutputSettings {
  double interval = 0.0;         // point frames (particles.pvd)
  double global_interval = 0.0;  // global.csv rows
  double tip_interval = 0.0;     // crack_tips.csv rows (methods with a tip table)
  std::set<std::string> fields;  // point arrays written in each frame
};

struct RunSettings {
  std::string title;
  double end_time = 0.0;
  double dt = 0.0;
  double stable_dt = 0.0;  // the method's stable limit at the start
  double damping = 0.0;    // kinetic damping coefficient kappa (1/s), "damping.kinetic"
  double energy_blowup_factor = 10.0;
  OutputSettings output;
  std::vector<std::string> warnings;  // doubts about the scene that are not errors (printed by the CLI)
};

}  // namespace cleave
