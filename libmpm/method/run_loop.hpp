// The one run loop, for every method: steps a Method to its end time and writes the frame series
// (particles.pvd + VTU frames, and any other series the method has, such as cracks.pvd),
// global.csv, crack_tips.csv when the method has a tip table, checkpoint.bin at every frame, and
// run.json whose "status" says whether the output is complete, still running (updated about once
// a second with step, time, frames and ETA), stopped on request (SIGINT/SIGTERM: a checkpoint at
// that step, and the command that resumes), or aborted by a detected problem or a failed write.
// `--resume` continues from the last checkpoint bit for bit. One run at a time per directory
// (io/output_lock.hpp). The last run.json (complete, stopped, aborted) records what each part of
// the run cost in wall time ("costs", core/part_costs.hpp).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "libmpm/core/part_costs.hpp"
#include "libmpm/method/method.hpp"

namespace cleave {

struct RunProgress {
  long step = 0;
  double time = 0.0, end_time = 0.0, wall_s = 0.0, eta_s = 0.0;
  long frames = 0;  // frames of the run written so far, resumed parts included
};

struct RunOptions {
  std::filesystem::path out;
  bool resume = false;
  std::function<void(const RunProgress&)> progress;  // called about every progress_interval_s
  std::function<void(const std::string&)> log;       // warnings found while stepping
  std::function<void()> between_steps;               // after every step (the CLI's ThreadGovernor)
  double progress_interval_s = 0.5;
  double status_interval_s = 1.0;  // run.json while running: at every frame, else at most this often
  uint64_t scene_hash = 0;
  // SIGINT/SIGTERM stop the run after its step with a checkpoint there (RunStopped), and SIGXFSZ
  // is ignored (method/stop_signals.hpp), while the run goes.
  bool handle_signals = true;
  std::string command;         // the command line, named in run.lock for a refused second run
  std::string resume_command;  // what run.json and the stop message tell the user to run
  // The scene's length unit ("mm"; empty: SI), recorded in run.json as "length_unit" so that tools
  // reading the run (cleave fit) take lengths in the units the scene was written in.
  std::string length_unit;
};

struct RunSummary {
  long steps = 0;  // the step count at the end (a resumed run's steps before the resume included)
  double time = 0.0, wall_s = 0.0;
  int frames = 0;  // frames written by this call
  bool resumed = false;
  long first_step = 0;  // the step this call started from (the checkpoint's when resumed)
  double max_energy_drift = 0.0;  // max |E - E0| / max(E0, max E) over global rows (no loads/damping)
  // What each part of this call cost (core/part_costs.hpp; a resumed run: the resumed part only), up
  // to the last run.json, which records the same as "costs".
  costs::Totals costs;

  // Takes the total energy of one global row: E0 is the first, the drift is folded into
  // max_energy_drift.
  void observe_energy(double total) {
    if (first_energy < 0) first_energy = total;
    largest_energy = std::max(largest_energy, total);
    const double scale = std::max(first_energy, largest_energy);
    if (scale > 0) max_energy_drift = std::max(max_energy_drift, std::fabs(total - first_energy) / scale);
  }
  double first_energy = -1.0, largest_energy = 0.0;
  // Energy made from nothing: the growth of (kinetic + strain) less the external work since the first
  // global row, over the largest energy or work seen. Damping and contact friction only lower it, so
  // a gain is numerical (crack contact, a step near the limit).
  double max_energy_gain = 0.0;
  void observe_balance(double total, double work) {
    if (!have_balance) first_balance = total - work, have_balance = true;
    balance_scale = std::max({balance_scale, std::fabs(total), std::fabs(work)});
    if (balance_scale > 0)
      max_energy_gain = std::max(max_energy_gain, (total - work - first_balance) / balance_scale);
  }
  bool have_balance = false;
  double first_balance = 0.0, balance_scale = 0.0;
};

// Throws RunAborted (after writing the last state) when a step detects a problem, RunOutputFailed
// when an output cannot be written, RunStopped on SIGINT/SIGTERM, RunRefused when the run cannot
// start (checkpoint missing or of another scene, method, dimension or format; directory locked).
template <int Dim>
RunSummary run_method(Method<Dim>& method, const RunOptions& opt);

uint64_t scene_hash(const nlohmann::json& scene);

}  // namespace cleave
