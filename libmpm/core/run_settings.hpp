// What every scene sets for its run, whatever the method: read by the shared scene sections
// (scene/sections.hpp) and held by each method's model, so the one run loop (method/run_loop.hpp)
// needs nothing else from the scene.
#pragma once
#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

namespace cleave {

struct OutputSettings {
  double interval = 0.0;         // point frames (particles.pvd)
  double global_interval = 0.0;  // global.csv rows
  double tip_interval = 0.0;     // crack_tips.csv rows (methods with a tip table)
  std::set<std::string> fields;  // point arrays written in each frame
  bool zlib = false;     // "compression": "zlib" (frames' appended data deflated) or "none"
  bool float32 = false;  // "precision": "float32" (points and point data) or "float64"
};

struct RunSettings {
  std::string title;
  double end_time = 0.0;
  double dt = 0.0;
  double stable_dt = 0.0;  // the method's stable limit at the start
  double damping = 0.0;    // kinetic damping coefficient kappa (1/s), "damping.kinetic"
  // "static.tolerance" (> 0): dynamic relaxation to the static state (method/relaxation.hpp): damping
  // kept critical, the run ends when static; time.end is then the latest it may end. 0: dynamics.
  double static_tolerance = 0.0;
  double energy_blowup_factor = 10.0;
  OutputSettings output;
  std::vector<std::string> warnings;  // doubts about the scene that are not errors (printed by the CLI)
  // The builder's estimate of the memory the run holds (bytes; 0: none), and the scene key that sets
  // the number of points (the resolution), which the resource checks name (scene/budget.hpp).
  double memory_bytes = 0.0;
  std::string size_key = "resolution";
};

// Steps to the end time, and the records (frames, rows) a cadence of `interval` writes: the run loop
// writes the first at t = 0 and at most one per step (method/run_loop.cpp). As doubles: a bad scene
// may ask for more than a long holds, and the scene reader refuses that (scene/sections.cpp).
inline double steps_to_end(const RunSettings& s) { return std::ceil(s.end_time / s.dt - 1e-9); }
inline double records_to_end(const RunSettings& s, double interval) {
  return std::min(steps_to_end(s), std::ceil(s.end_time / interval - 1e-9)) + 1.0;
}

}  // namespace cleave
