#include "libmpm/method/run_loop.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "libmpm/core/error.hpp"
#include "libmpm/core/part_costs.hpp"
#include "libmpm/io/csv_writer.hpp"
#include "libmpm/io/output_lock.hpp"
#include "libmpm/io/pvd_writer.hpp"
#include "libmpm/io/run_files.hpp"
#include "libmpm/io/vtu_writer.hpp"
#include "libmpm/method/checkpoint.hpp"
#include "libmpm/method/stop_signals.hpp"

namespace cleave {
namespace fs = std::filesystem;

uint64_t scene_hash(const nlohmann::json& scene) {
  // FNV-1a of the canonical dump: stable across runs and builds.
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : scene.dump()) h = (h ^ c) * 1099511628211ull;
  return h;
}

namespace {

// The energy gain (RunSummary::observe_balance) that cleave run reports: twice the largest apparent
// gain of a sound run seen, block_penny_crack.json's 5.0 % (with or without contact: the measure of
// the face tractions' work on its coarse 3D faces; 2D at 1 mm about 2.5 %, docs/validation.md).
constexpr double kEnergyGainWarning = 0.10;

// Feeds RunSummary::observe_balance the total_energy_J and external_work_J of every row of a
// global.csv (a resumed run's history); a file without them feeds nothing.
void replay_balance(const fs::path& csv, RunSummary& sum) {
  std::ifstream in(csv);
  std::string line;
  if (!std::getline(in, line)) return;
  int e = -1, w = -1, k = 0;
  for (std::stringstream ss(line); std::getline(ss, line, ','); ++k) {
    if (line == "total_energy_J") e = k;
    if (line == "external_work_J") w = k;
  }
  if (e < 0 || w < 0) return;
  while (std::getline(in, line)) {
    std::vector<double> v;
    for (std::stringstream ss(line); std::getline(ss, line, ',');) v.push_back(std::strtod(line.c_str(), nullptr));
    if (static_cast<int>(v.size()) > std::max(e, w)) sum.observe_balance(v[e], v[w]);
  }
}

// A failed write of one of the run's outputs; handled once, at the end of run_method.
struct OutputFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// `what` with the cause errno names appended, unless the writer already named it.
std::string with_cause(const std::string& what, int err) {
  if (err == 0) return what;
  const std::string cause = std::strerror(err);
  return what.find(cause) != std::string::npos ? what : what + ": " + cause;
}

std::string at_step(long step, double t) {
  std::ostringstream s;
  s << "step " << step << ", time " << t << " s: ";
  return s.str();
}

// run.json's "costs": the wall time and the seconds of each part the run switched on.
nlohmann::json costs_json(const costs::Totals& t) {
  nlohmann::json parts = nlohmann::json::object();
  for (int p = 0; p < costs::kParts; ++p)
    if (t.on(p)) parts[costs::key(p)] = t.seconds[p];
  return {{"wall_s", t.wall_s}, {"parts", parts}};
}

}  // namespace

template <int Dim>
RunSummary run_method(Method<Dim>& method, const RunOptions& opt) {
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  // What each part of this call costs (core/part_costs.hpp): the writes below are output, the
  // method charges its own parts inside the step and its tip rows, the rest is the step's.
  costs::Ledger ledger;
  const costs::Activate active_ledger(ledger);
  const RunSettings& set = method.settings();
  const fs::path out = opt.out;
  const fs::path ck_path = out / "checkpoint.bin", csv_path = out / "global.csv", tips_path = out / method.tip_file();
  const fs::path events_path = out / method.event_file();
  if (opt.resume && !fs::exists(ck_path)) throw RunRefused(ck_path.string() + ": no checkpoint to resume from");
  fs::create_directories(out);
  // Before anything in the directory is touched: a second run into it is refused here.
  const io::OutputLock lock(out, io::describe_this_process() + (opt.command.empty() ? "" : ": " + opt.command));
  std::optional<StopSignals> signals;
  if (opt.handle_signals) signals.emplace();
  const std::string resume_command =
      opt.resume_command.empty() ? "cleave run SCENE --out " + out.string() + " --resume" : opt.resume_command;

  const std::vector<std::string> series = method.frame_series();
  std::vector<std::string> any_series = {"particles", "cracks"};  // a directory may hold another method's run
  for (const auto& s : series)
    if (std::find(any_series.begin(), any_series.end(), s) == any_series.end()) any_series.push_back(s);
  const std::vector<std::string> run_files = {"global.csv", "checkpoint.bin", "run.json", "crack_tips.csv",
                                                "crack_fronts.csv", "crack_growth.csv"};
  {
    const costs::Scope cost(costs::Output);
    io::remove_temporaries(out, any_series, run_files);  // what a killed run's atomic writes left
  }
  std::vector<io::PvdIndex> pvd;
  for (const auto& s : series) pvd.emplace_back(out / (s + ".pvd"));
  const std::vector<std::string> tip_cols = method.tip_columns();
  const bool tips = !tip_cols.empty();
  const std::vector<std::string> event_cols = method.event_columns();
  const bool events = !event_cols.empty();

  LoopCounters ck;
  long ck_step = -1;  // the checkpoint --resume would continue from (-1: none yet)
  double ck_time = 0.0;
  RunSummary sum;
  sum.resumed = opt.resume;
  if (opt.resume) {
    const costs::Scope cost(costs::Output);
    ck = read_checkpoint<Dim>(ck_path, method, opt.scene_hash);
    ck_step = method.step_count();
    ck_time = method.time();
    for (std::size_t k = 0; k < series.size(); ++k) pvd[k] = io::resumed_series(out / (series[k] + ".pvd"), method.time());
  }
  sum.first_step = method.step_count();

  // Every write of an output goes through here, so that a full disk or a file size limit is named
  // (the writer's message, with errno's cause) and handled once, below.
  auto output = [&](auto&& write) {
    const costs::Scope cost(costs::Output);
    errno = 0;
    try {
      write();
    } catch (const std::invalid_argument&) {
      throw;  // a bug in what was written, not the disk
    } catch (const std::runtime_error& e) {
      throw OutputFailure(with_cause(e.what(), errno));
    }
  };

  const double t_start = method.time();  // ETA from the progress since this process started
  auto progress_now = [&]() {
    RunProgress p;
    p.step = method.step_count();
    p.time = method.time();
    p.end_time = set.end_time;
    p.wall_s = std::chrono::duration<double>(clock::now() - t0).count();
    const double frac = (p.time - t_start) / std::max(set.end_time - t_start, 1e-300);
    p.eta_s = frac > 0 ? p.wall_s * (1.0 - frac) / frac : 0.0;
    p.frames = ck.next_frame;
    return p;
  };
  auto info = [&](const std::string& s) {
    nlohmann::json j = method.run_info();
    j["method"] = method.name();
    j["end_time"] = set.end_time;
    j["frames"] = ck.next_frame;
    j["length_unit"] = opt.length_unit.empty() ? "m" : opt.length_unit;
    if (ck_step >= 0) j["checkpoint"] = {{"step", ck_step}, {"time", ck_time}};
    if (s == "running") {
      const RunProgress p = progress_now();
      j["wall_s"] = p.wall_s;
      j["eta_s"] = p.eta_s;
      j["pid"] = ::getpid();
    }
    if (s == "stopped" || (s == "aborted" && ck_step >= 0)) j["resume"] = resume_command;
    if (s != "running") j["energy_gain"] = sum.max_energy_gain;
    if (s != "running") {  // the last word: what the parts cost up to it (the summary's too)
      sum.costs = ledger.totals();
      j["costs"] = costs_json(sum.costs);
    }
    return j;
  };
  auto status = [&](const std::string& s, const std::string& msg) {
    output([&] { io::write_run_status(out, s, msg, method.step_count(), method.time(), info(s)); });
  };
  auto last_status = clock::now();
  auto status_running = [&] {
    status("running", "");
    last_status = clock::now();
  };

  try {
    output([&] {
      if (opt.resume) {
        io::CsvSeries::truncate_after(csv_path, method.time());
        io::CsvSeries::truncate_after(tips_path, method.time());
        if (events) io::CsvSeries::truncate_after(events_path, method.time());
      } else {
        // A fresh run replaces the outputs of an earlier one in the same directory (of any method).
        io::remove_run_outputs(out, any_series, run_files);
      }
    });
    // A resumed run's energy balance starts where the first part's did: replayed from the global.csv
    // rows up to the checkpoint (written with round-trip precision), so run.json's energy_gain is that
    // of an uninterrupted run.
    if (opt.resume) replay_balance(csv_path, sum);
    std::optional<io::CsvSeries> csv, tip_csv, event_csv;
    output([&] {
      csv.emplace(csv_path, method.global_columns(), opt.resume);
      if (tips) tip_csv.emplace(tips_path, tip_cols, opt.resume);
      if (events) event_csv.emplace(events_path, event_cols, opt.resume);
    });
    status_running();

    const double eps = 1e-9 * set.dt;
    auto write_frame = [&]() {
      output([&] {
        for (std::size_t k = 0; k < series.size(); ++k) {
          const std::string name = io::frame_file_name(series[k], static_cast<int>(ck.next_frame));
          io::write_vtu(out / name, method.frame(k), {.zlib = set.output.zlib, .float32 = set.output.float32});
          pvd[k].add(method.time(), name);
          pvd[k].write();
        }
      });
      ++ck.next_frame;
      ++sum.frames;
    };
    auto checkpoint = [&]() {
      ck.scene_hash = opt.scene_hash;
      output([&] {
        // The series' rows up to this step reach the disk before the checkpoint that resumes after them.
        for (auto* series_csv : {&csv, &tip_csv, &event_csv})
          if (*series_csv) (*series_csv)->sync();
        write_checkpoint<Dim>(ck_path, method, ck);
      });
      ck_step = method.step_count();
      ck_time = method.time();
    };
    bool gain_reported = sum.max_energy_gain > kEnergyGainWarning;  // (a resumed run's first part warned)
    auto record_global = [&]() {
      const costs::Scope cost(costs::Output);
      const GlobalRow g = method.global_row();
      output([&] { csv->row(g.values); });
      sum.observe_energy(g.total_energy);
      sum.observe_balance(g.total_energy, g.external_work);
      if (!gain_reported && sum.max_energy_gain > kEnergyGainWarning && opt.log) {
        gain_reported = true;
        char b[400];
        std::snprintf(b, sizeof b, "energy not conserved: kinetic + strain energy less the external work has grown by "
                      "%.1f %% of the largest energy by t = %.6g s; no physics adds energy, so the run's results may "
                      "be wrong (crack contact and a time step near the stable limit are known causes: "
                      "docs/validation.md, \"Stability at the extremes\"); run.json records the largest gain",
                      100 * sum.max_energy_gain, method.time());
        opt.log(b);
      }
      return g;
    };
    auto record_tips = [&]() {
      const costs::Scope cost(costs::Output);  // J/K or tip tracking inside, charged by the method
      const auto rows = method.tip_rows();
      output([&] {
        for (const auto& row : rows) tip_csv->row(row);
      });
    };
    auto abort_run = [&](const std::string& msg) {
      try {
        write_frame();
      } catch (const OutputFailure& e) {
        throw OutputFailure(std::string(e.what()) + ", the state at a detected problem (" + msg + ")");
      }
      status("aborted", msg);
      throw RunAborted(msg);
    };
    // A stop on request: the step is done; its state goes to a checkpoint (not a frame, so the
    // resumed run's files are those of an uninterrupted one) and run.json says how to go on.
    auto stop_run = [&](int sig) {
      checkpoint();
      std::ostringstream msg;
      msg << "stopped by " << signal_name(sig) << " at step " << method.step_count() << ", time " << method.time()
          << " s; resume with: " << resume_command;
      status("stopped", msg.str());
      throw RunStopped(sig, msg.str());
    };
    if (!opt.resume) {
      record_global();
      if (tips) record_tips();
      write_frame();
      ck.next_frame_time = set.output.interval;
      ck.next_global_time = set.output.global_interval;
      ck.next_tip_time = set.output.tip_interval;
      checkpoint();
      status_running();
    }

    auto last_report = clock::now();
    while (method.time() < set.end_time - eps) {
      if (const int sig = stop_requested()) stop_run(sig);
      StepProblem problem;
      {
        const costs::Scope cost(costs::Step);
        problem = method.step();
      }
      if (opt.between_steps) opt.between_steps();
      if (events)
        if (const auto rows = method.take_event_rows(); !rows.empty())
          output([&] {
            for (const auto& row : rows) event_csv->row(row);
          });
      const double t = method.time();
      const bool last = t >= set.end_time - eps || method.static_reached();
      if (opt.log)
        if (const std::string w = method.take_warning(); !w.empty()) opt.log(w);
      // The checks: the energy's at every global.csv row, and at a step with a problem too; every
      // one that trips is reported, the energy's first, then the step's problem.
      const bool global_due = t >= ck.next_global_time - eps || last;
      if (problem || global_due) {
        const GlobalRow g = record_global();
        if (global_due) ck.next_global_time += set.output.global_interval;
        std::vector<std::string> tripped;
        // The reference: the energy at the start or the work done on the bodies since. Where both
        // are still zero (bodies at rest, a load ramped from zero) there is none yet, and the test
        // waits for one: velocity-Verlet (peridynamics) gives the first step's load its half kick
        // of kinetic energy before the work counts any displacement, which is no blow-up (it
        // stopped a sound run at step 1 when the step was as long as global_interval).
        const double ref = std::max(sum.first_energy, std::fabs(g.external_work));
        if (!std::isfinite(g.total_energy)) {
          tripped.push_back("energy is not finite");
        } else if (ref > 0.0 && g.total_energy > set.energy_blowup_factor * ref && g.total_energy > 1e-12) {
          std::ostringstream msg;
          // Name the fastest point: where the blow-up is.
          msg << "energy blow-up, total energy " << g.total_energy << " J exceeds " << set.energy_blowup_factor
              << " x the reference " << ref << " J; fastest " << method.fastest_point();
          tripped.push_back(msg.str());
        }
        if (problem) tripped.push_back(problem.what);
        if (!tripped.empty()) {
          std::string msg = at_step(method.step_count(), t) + tripped[0];
          for (std::size_t k = 1; k < tripped.size(); ++k) msg += "; also " + tripped[k];
          abort_run(msg);
        }
      }
      if (tips && (t >= ck.next_tip_time - eps || last)) {
        record_tips();
        while (ck.next_tip_time <= t + eps) ck.next_tip_time += set.output.tip_interval;
      }
      if (t >= ck.next_frame_time - eps || last) {
        write_frame();
        ck.next_frame_time += set.output.interval;
        checkpoint();
        if (!last) status_running();
      } else if (std::chrono::duration<double>(clock::now() - last_status).count() >= opt.status_interval_s) {
        status_running();  // so that run.json can be watched between frames
      }
      if (opt.progress && std::chrono::duration<double>(clock::now() - last_report).count() >= opt.progress_interval_s) {
        last_report = clock::now();
        const costs::Scope cost(costs::Output);
        opt.progress(progress_now());
      }
      if (last) break;  // time.end, or a static state reached (dynamic relaxation)
    }
    if (set.static_tolerance > 0) {
      std::ostringstream msg;
      if (!method.static_reached()) {
        msg << "not static by time.end = " << set.end_time << " s: " << method.relaxation_state()
            << "; raise time.end or loosen static.tolerance (the last frame is the state at time.end)";
        status("aborted", msg.str());
        throw RunAborted(msg.str());
      }
      msg << "static at t = " << method.time() << " s, step " << method.step_count() << ": " << method.relaxation_state();
      status("complete", msg.str());
    } else {
      // A method that ends the run by its own criterion (PEM's equilibrium or separation) says which.
      status("complete", method.static_reached() ? method.relaxation_state() : "");
    }
  } catch (const OutputFailure& e) {
    // Only temporaries of the failed writes go: the last complete frame and checkpoint stay, and
    // run.json says why, even on a full disk (write_final_run_status).
    io::remove_temporaries(out, any_series, run_files);
    const std::string msg = at_step(method.step_count(), method.time()) + e.what();
    const std::string also =
        io::write_final_run_status(out, "aborted", msg, method.step_count(), method.time(), info("aborted"));
    throw RunOutputFailed(also.empty() ? msg : msg + "; run.json could not be updated either: " + also);
  }
  sum.steps = method.step_count();
  sum.time = method.time();
  sum.wall_s = std::chrono::duration<double>(clock::now() - t0).count();
  return sum;
}

template RunSummary run_method<2>(Method<2>&, const RunOptions&);
template RunSummary run_method<3>(Method<3>&, const RunOptions&);

}  // namespace cleave
