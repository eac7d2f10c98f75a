// cleave: the command-line program. `cleave --help` documents every sub-command and option.
#include <omp.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "apps/cleave/progress.hpp"
#include "apps/cleave/render_cli.hpp"
#include "apps/cleave/study_cli.hpp"
#include "libmpm/core/error.hpp"
#include "libmpm/core/resources.hpp"
#include "libmpm/core/thread_governor.hpp"
#include "libmpm/method/run_scene.hpp"
#include "libmpm/scene/scene.hpp"

namespace fs = std::filesystem;
using namespace cleave;

namespace {

constexpr int kOk = 0, kFailure = 1, kBadInput = 2, kAborted = 3;

const char* kHelp = R"(cleave - dynamic fracture with particle methods

Usage:
  cleave run SCENE [--out DIR] [--threads N] [--resume] [--quiet] [--force] [--set KEY=VALUE ...]
  cleave check SCENE [--set KEY=VALUE ...]
  cleave render OUT [options]       images and movies (stress colours, photoelastic fringes)
  cleave compare OUT --photo IMG --frame SPEC --map X0,Y0,SCALE[,ANGLE] [--points FILE]
  cleave plot OUT                   energy and J/K plots
  cleave fit [OUT] --points FILE ...  K_I, K_II, T from fringe orders; calibration against a run
                                    (cleave fit --help)
  cleave study STUDY.json [--out DIR] runs a speed-accuracy study: the runs, their errors and
                                    costs, work-precision diagrams (cleave study --help)
  cleave --help | --version         (cleave render --help: the renderer's options)

Commands:
  run     Simulate SCENE (a JSON scene, see docs/scenes.md). Writes into DIR:
            particles.pvd + particles_NNNNNN.vtu   particle time series (VTK XML)
            cracks.pvd + cracks_NNNNNN.vtu         crack paths, surfaces and opening (cracked
                                                   scenes only)
            global.csv                             energies, external work, momentum
            crack_tips.csv                         J1, J2, KI, KII per crack tip (scenes with
                                                   crack_tips)
            checkpoint.bin                         restart state at the last frame (or stop)
            run.json                               status: running | complete | stopped |
                                                   aborted; step, time, frames, ETA; at
                                                   the end the cost of each part (costs)
            run.lock                               held while a run goes (one run per DIR)
          Shows progress (step, simulated time, wall time, ETA) on stderr, and on stdout a
          one-line summary and a cost line: each part the scene switched on (step, crack
          fields, contact, J/K, tip tracking, output) as a share of the wall time.
  check   Validate SCENE without running it: every bad value is reported with its key
          path and reason. Prints what the run would build.

Options:
  --out DIR      output directory (default: SCENE's file name without .json, + "_out")
  --threads N    exactly N OpenMP threads; default: up to OMP_NUM_THREADS or all cores, fewer
                 while other processes keep cores busy (measured every second); results are the
                 same for any N
  --resume       continue a stopped run from DIR/checkpoint.bin (same scene)
  --quiet        no progress line
  --force        run even when the estimates say it will not fit: more memory than the
                 machine has available, or more output than DIR's disk has free
  --set K=V      override one scene value before validation; K is a key path as in error
                 messages (mpm.stress_update, bodies[1].velocity), V is JSON or a plain string;
                 null removes the key: --set mpm.stress_update=USL --set resolution=1
                 --set 'time.end=2.5' --set damping=null
  --help         this text
  --version      program version

Exit status: 0 success; 1 internal error, or an I/O error before the run started (DIR
cannot be created); 2 bad scene or command line, a checkpoint that --resume cannot use
(another scene, method, dimension or an older format), or DIR in use by another run
(nothing is written); 3 the run stopped on a detected problem
(particle left the grid, NaN, energy blow-up; its last state is written) or an output
could not be written (disk full, ulimit -f; the last complete frame and checkpoint
stay); run.json says "aborted" and why; 130 / 143 stopped by SIGINT / SIGTERM after
the current step, with a checkpoint there; run.json says "stopped" and how to resume
(a second signal kills at once).
)";

struct Args {
  std::string command, scene, out;
  int threads = 0;
  bool resume = false, quiet = false, force = false;
  std::vector<std::string> sets;
  std::vector<std::string> argv;  // as typed: run.lock names it, the resume command repeats it
};

int usage_error(const std::string& msg) {
  std::fprintf(stderr, "cleave: %s\n(see cleave --help)\n", msg.c_str());
  return kBadInput;
}

int run_scene_command(const nlohmann::json& scene, const Args& a) {
  SceneMethod method = SceneMethod::build(scene);
  for (const auto& w : method.settings().warnings) std::fprintf(stderr, "cleave: warning: %s\n", w.c_str());
  fs::path out = a.out;
  if (out.empty()) out = fs::path(a.scene).stem().string() + "_out";
  if (a.command == "check") {
    auto lines = method.describe();
    const RunEstimate est = method.estimate();
    for (const auto& l : describe_estimate(est, out)) lines.push_back(l);
    for (const auto& [file, columns] : method.tables()) {  // what plot and study can read
      std::string l = "table " + file + ":";
      for (const auto& c : columns) l += " " + c;
      lines.push_back(l);
    }
    for (std::size_t i = 0; i < lines.size(); ++i) std::printf("%s%s\n", i ? "" : "scene OK: ", lines[i].c_str());
    try {  // check writes nothing, so a disk too small for the run is a warning here
      check_disk(est, out);
    } catch (const SceneError& e) {
      std::fprintf(stderr, "cleave: warning: %s: %s (cleave run refuses it)\n", e.key_path().c_str(), e.reason().c_str());
    }
    return kOk;
  }
  app::ProgressPrinter printer;
  RunOptions opt;
  opt.out = out;
  opt.resume = a.resume;
  opt.command = app::shell_command(a.argv, false);
  opt.resume_command = app::shell_command(a.argv, true);
  if (const auto u = scene.find("units"); u != scene.end() && u->is_object() && u->contains("length"))
    opt.length_unit = (*u)["length"].get<std::string>();  // validated by SceneMethod::build
  opt.progress_interval_s = printer.interval();
  if (!a.quiet) opt.progress = [&](const RunProgress& p) { printer(p); };
  long warnings = 0;
  opt.log = [&](const std::string& w) {  // the first few in full, then a count at the end
    if (++warnings <= 5) std::fprintf(stderr, "\ncleave: warning: %s\n", w.c_str());
  };
  // Without --threads: fewer threads while other processes hold cores (core/thread_governor.hpp).
  std::optional<ThreadGovernor> governor;
  if (a.threads == 0 && omp_get_max_threads() > 1) {
    governor.emplace(omp_get_max_threads());
    opt.between_steps = [&] {
      if (const int n = governor->poll(); n > 0 && !a.quiet)
        std::fprintf(stderr, "\ncleave: other processes keep %.1f of %d cores busy: %d thread%s from now on\n",
                     governor->other_cores(), omp_get_num_procs(), n, n == 1 ? "" : "s");
    };
  }
  try {
    const RunSummary s = method.run(opt);
    printer.finish();
    if (warnings > 5) std::fprintf(stderr, "cleave: %ld warnings in all (5 shown)\n", warnings);
    const auto [work, unit] = method.work_per_step();
    std::printf("%s\n", app::summary_line(s, work, unit, omp_get_max_threads(), out.string()).c_str());
    std::printf("%s\n", app::cost_line(s.costs).c_str());  // what each part the scene switched on cost
    return kOk;
  } catch (const RunStopped& e) {
    printer.finish();
    std::fprintf(stderr, "cleave: %s\n", e.what());
    return 128 + e.signal();  // the shell's convention for a process ended by that signal
  } catch (const RunOutputFailed& e) {
    printer.finish();
    std::fprintf(stderr, "cleave: run stopped: %s\nthe frames and checkpoint written before are kept in %s; %s says "
                 "\"aborted\"\n", e.what(), out.string().c_str(), (out / "run.json").string().c_str());
    return kAborted;
  } catch (const RunAborted& e) {
    printer.finish();
    std::fprintf(stderr, "cleave: run stopped: %s\nlast state written to %s; %s says \"aborted\"\n", e.what(),
                 out.string().c_str(), (out / "run.json").string().c_str());
    return kAborted;
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> argv_s(argv + 1, argv + argc);
  if (!argv_s.empty() && (argv_s[0] == "render" || argv_s[0] == "compare" || argv_s[0] == "plot"))
    return app::viz_command(argv_s);
  if (!argv_s.empty() && argv_s[0] == "fit") return app::fit_command(argv_s);
  if (!argv_s.empty() && argv_s[0] == "study") return app::study_command(argv_s);
  Args a;
  a.argv.assign(argv, argv + argc);
  for (std::size_t i = 0; i < argv_s.size(); ++i) {
    const std::string& s = argv_s[i];
    auto value = [&](const char* opt) -> std::string {
      if (i + 1 >= argv_s.size()) throw std::invalid_argument(std::string(opt) + " needs a value");
      return argv_s[++i];
    };
    try {
      if (s == "--help" || s == "-h") {
        std::fputs(kHelp, stdout);
        return kOk;
      } else if (s == "--version") {
        std::puts("cleave 0.1");
        return kOk;
      } else if (s == "--out") {
        a.out = value("--out");
      } else if (s == "--threads") {
        const std::string v = value("--threads");
        std::size_t pos = 0;
        a.threads = std::stoi(v, &pos);
        if (pos != v.size() || a.threads < 1) throw std::invalid_argument("--threads needs a positive integer");
      } else if (s == "--resume") {
        a.resume = true;
      } else if (s == "--set") {
        a.sets.push_back(value("--set"));
      } else if (s == "--force") {
        a.force = true;
      } else if (s == "--quiet") {
        a.quiet = true;
      } else if (!s.empty() && s[0] == '-') {
        return usage_error("unknown option '" + s + "'");
      } else if (a.command.empty()) {
        a.command = s;
      } else if (a.scene.empty()) {
        a.scene = s;
      } else {
        return usage_error("unexpected argument '" + s + "'");
      }
    } catch (const std::exception& e) {
      return usage_error(std::string(e.what()).find("stoi") != std::string::npos ? "--threads needs a positive integer"
                                                                                : e.what());
    }
  }
  if (a.command.empty()) return usage_error("no command given");
  if (a.command != "run" && a.command != "check") return usage_error("unknown command '" + a.command + "'");
  if (a.scene.empty()) return usage_error(a.command + " needs a SCENE file");
  if (a.threads > 0) omp_set_num_threads(a.threads);

  try {
    nlohmann::json scene = load_scene_file(a.scene);
    set_resource_checks_forced(a.force);  // before the scene builds: its memory check reads it
    apply_overrides(scene, a.sets);
    return run_scene_command(scene, a);
  } catch (const SceneError& e) {
    if (e.key_path().empty()) std::fprintf(stderr, "cleave: %s\n", e.reason().c_str());  // the file itself
    else std::fprintf(stderr, "cleave: %s: error at '%s': %s\n", a.scene.c_str(), e.key_path().c_str(), e.reason().c_str());
    return kBadInput;
  } catch (const RunRefused& e) {
    std::fprintf(stderr, "cleave: cannot run: %s\n", e.what());
    return kBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cleave: error: %s\n", e.what());
    return kFailure;
  }
}
