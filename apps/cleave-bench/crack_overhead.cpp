// cleave-bench-crack: the cost of the crack machinery (seed 002 §3.5 reports ~10 %; target <= 5 %).
// The DCB of data/scenes/dcb_crack.json refined to >= 100 000 particles (uGIMP, USAVG), built twice
// in one process, with its crack and without it, and stepped in alternating blocks (cracked first in
// odd repetitions, uncracked first in even ones, so that a drift of the machine's load affects both
// alike); prints ns per particle-step of each block, their ratio per repetition, and the median and
// range of the ratios. Wall-clock time is the figure; printed beside it are the ratio of the process
// CPU times (with one thread, insensitive to time slices lost to other processes on a shared
// machine) and the ratio of the fastest block of each (the least disturbed by other processes).
// Usage: cleave-bench-crack [--case dcb|rod3d|fronts|tips|costs] [--cell MM] [--steps N] [--reps R] [--only cracked|uncracked|evaluation] [--null]
//          [--integral contour|domain]
// --case costs: what `cleave run` reports each part costs (core/part_costs.hpp), the DCB (2 mm cells
// unless --cell) run to its end with its crack and J/K at the tip, and without the crack; exits 1
// unless the uncracked run's crack fields, contact and J/K parts recorded no scope and no time.
// --case fronts: the cost of evaluating J and K at every front node (crack_tips in 3D, issue 17) against
// one step, the rod at 3 mm cells (480 000 particles) stepped to 30 us (the load has reached the crack), then a step and
// an evaluation alternately (which first alternates too), R = 10 repetitions; --only evaluation: R evaluations
// of the state at 30 us and nothing else (for a profiler); --integral domain: J1 by the domain integral
// (crack_tips.integral, with eq. 33's inertia term) instead of the scene's contour.
// --case tips: the same for the 2D tip of the DCB (0.5 mm cells unless --cell, 57 600 particles) with each
// contour setting of docs/validation.md's "The defaults", R = 20 repetitions each.
// --case rod3d: the same for 3D cracks, the quarter rod of seed 000 §4.1 (data/scenes/rod_elliptical_crack.json)
// at 2.5 mm cells, 829 440 particles, 20 repetitions, from 30 us (the load has reached the crack).
// (dcb defaults: 0.25 mm cells = 230 400 particles, blocks of 2 steps, 150 repetitions, after 5 warm-up
// steps of each model; --only steps one of the two, for profiling; --null builds both models
// without the crack, so the figure it prints is the benchmark's own bias and noise, not zero).
// Short blocks keep the two halves of a repetition close in time, so that a change of the machine's
// load hits both: on the shared 2-core VM, --null read -3.7 ... +3.5 % with blocks of 10 steps x 30
// and -0.5 ... +0.3 % with 2 steps x 150 (docs/performance.md).
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "libmpm/method/run_scene.hpp"
#include "libmpm/mpm/mpm_scene.hpp"
#include "libmpm/mpm/mpm_step.hpp"
#include "libmpm/mpm/step_timers.hpp"

using namespace cleave;

namespace {

double cpu_seconds() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

template <int Dim>
Model<Dim> with_or_without_crack(nlohmann::json scene, bool cracked) {
  if (!cracked) scene.erase("cracks");
  return build_model<Dim>(scene);
}

template <int Dim>
struct Run {
  Model<Dim> model;
  std::unique_ptr<Stepper<Dim>> stepper;
  // Warm-up: 5 steps (first contacts, allocations), and on to `loaded_at` (s) when it is given: the
  // time at which the load has reached the crack. A crack at rest costs little: its index and its
  // particles' keys are kept while its points stay the same, bit for bit (spatial_index.hpp).
  Run(const nlohmann::json& scene, bool cracked, double loaded_at = 0.0)
      : model(with_or_without_crack<Dim>(scene, cracked)) {
    stepper = make_stepper<Dim>(model);
    for (int i = 0; i < 5 || stepper->time() < loaded_at; ++i) stepper->step();
  }
  std::vector<double> task_seconds[step_timers::kSlots];  // with -DCLEAVE_STEP_TIMERS=ON: per task, per block
  // ns per particle-step of `steps` steps: wall clock and process CPU time.
  std::pair<double, double> time(int steps) {
    step_timers::reset();
    const double c0 = cpu_seconds();
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < steps; ++i) stepper->step();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double c = cpu_seconds() - c0, per = 1e9 / (double(steps) * double(model.particles.size()));
    for (int k = 0; k < step_timers::kSlots; ++k) task_seconds[k].push_back(step_timers::seconds[k] / steps);
    return {s * per, c * per};
  }
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

// A step and an evaluation alternately (which goes first alternates too): per repetition the two
// times in ms; returns the medians and the evaluation / step ratios' median, min and max.
struct Alternation {
  double step_ms, eval_ms, ratio, lo, hi;
};
template <class Step, class Eval>
Alternation alternate(int reps, Step&& step, Eval&& eval, const char* what) {
  std::vector<double> step_ms, eval_ms, ratio;
  using clock = std::chrono::steady_clock;
  const auto ms = [](clock::time_point a, clock::time_point b) { return 1e3 * std::chrono::duration<double>(b - a).count(); };
  for (int i = 0; i < reps; ++i) {
    double s = 0, e = 0;
    for (int k = 0; k < 2; ++k) {
      const auto t0 = clock::now();
      if ((i + k) % 2 == 0) step(), s = ms(t0, clock::now());
      else eval(), e = ms(t0, clock::now());
    }
    step_ms.push_back(s), eval_ms.push_back(e), ratio.push_back(e / s);
    std::printf("rep %d: step %.2f ms, %s %.2f ms, ratio %.3f\n", i + 1, s, what, e, e / s);
  }
  return {median(step_ms), median(eval_ms), median(ratio), *std::min_element(ratio.begin(), ratio.end()),
          *std::max_element(ratio.begin(), ratio.end())};
}

// --case fronts: an evaluation of every front node against a step, alternating.
// The rod's load reaches its crack at 26 us (step waves from its ends, 150 mm away, at 5.8 mm/us):
// --case fronts and rod3d time it from here on. (Until 2026-11-28 they began at 40 and 5 steps, with
// the crack still at rest, its index and keys kept from step to step.)
constexpr double kRodLoadedAt = 30e-6;

int bench_fronts(const nlohmann::json& scene, int reps, const std::string& only) {
  Model<3> m = build_model<3>(scene);
  auto stepper = make_stepper<3>(m);
  while (stepper->time() < kRodLoadedAt) stepper->step();
  std::size_t nodes = 0;
  if (only == "evaluation") {  // (for a profiler: the evaluations alone, of one state)
    const auto t0 = std::chrono::steady_clock::now();
    for (int r = 0; r < reps; ++r) nodes = stepper->crack_front_parameters(*m.crack_tips).size();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("rod (3D, elliptical crack), %zu particles, %d threads, %zu front nodes: evaluation %.2f ms (mean of %d)\n",
                m.particles.size(), omp_get_max_threads(), nodes, 1e3 * s / reps, reps);
    return 0;
  }
  const Alternation a = alternate(reps, [&] { stepper->step(); },
                                  [&] { nodes = stepper->crack_front_parameters(*m.crack_tips).size(); },
                                  "evaluation of the front nodes");
  std::printf("rod (3D, elliptical crack), %zu particles, %d threads, %zu front nodes: step %.1f ms, evaluation %.1f ms "
              "(%.2f ms per node), evaluation / step %.1f %% (per-rep range %.1f ... %.1f %%)\n",
              m.particles.size(), omp_get_max_threads(), nodes, a.step_ms, a.eval_ms,
              a.eval_ms / double(std::max<std::size_t>(nodes, 1)), 100 * a.ratio, 100 * a.lo, 100 * a.hi);
  return 0;
}

// --case tips: J and K at the DCB's tip with each contour setting (2D crack_tips: the 2-cell circle
// with eq. 32, the old default; 4 cells with eq. 32; the default, 4 cells with eq. 33; 6 cells with
// eq. 33) against one step, alternating, 100 steps into the loading.
int bench_tips(const nlohmann::json& scene, int reps) {
  Model<2> m = build_model<2>(scene);
  auto stepper = make_stepper<2>(m);
  for (int i = 0; i < 100; ++i) stepper->step();
  struct Setting {
    double radius;
    bool volume_term;
  };
  for (const Setting& c : {Setting{2, false}, Setting{4, false}, Setting{4, true}, Setting{6, true}}) {
    crack::TipSettings ts;
    ts.radius = c.radius, ts.volume_term = c.volume_term;
    const Alternation a = alternate(reps, [&] { stepper->step(); }, [&] { stepper->crack_tip_parameters(ts); },
                                    "J and K at the tip");
    std::printf("DCB (2D), %zu particles, %d threads, %g-cell circle, eq. %d: step %.2f ms, evaluation %.3f ms, "
                "evaluation / step %.2f %% (per-rep range %.2f ... %.2f %%)\n",
                m.particles.size(), omp_get_max_threads(), c.radius, c.volume_term ? 33 : 32, a.step_ms, a.eval_ms,
                100 * a.ratio, 100 * a.lo, 100 * a.hi);
  }
  return 0;
}

template <int Dim>
int bench(const char* what, const nlohmann::json& scene, int steps, int reps, const std::string& only, bool null_test,
          double loaded_at = 0.0);

// --case costs: the parts' costs of a cracked run beside an uncracked one; the uncracked one must
// pay nothing for cracks (no scope entered, no time).
int bench_costs(const nlohmann::json& cracked_scene) {
  nlohmann::json uncracked_scene = cracked_scene;
  uncracked_scene.erase("cracks");
  uncracked_scene.erase("crack_tips");
  const auto run = [](const nlohmann::json& scene, const std::string& tag) {
    RunOptions opt;
    opt.out = std::filesystem::temp_directory_path() / ("cleave-bench-costs-" + tag + "-" + std::to_string(getpid()));
    opt.handle_signals = false;
    const RunSummary s = run_scene(scene, {}, opt);
    std::filesystem::remove_all(opt.out);
    return s;
  };
  const RunSummary a = run(cracked_scene, "cracked"), b = run(uncracked_scene, "uncracked");
  std::printf("DCB, %ld steps, %d threads: seconds, share of the wall time, scopes entered\n", a.steps,
              omp_get_max_threads());
  std::printf("  %-13s %34s %34s\n", "part", "cracked, J/K at the tip", "uncracked");
  const auto cell = [](const costs::Totals& t, int p) {
    char c[64];
    std::snprintf(c, sizeof c, "%9.3f s %5.1f %% %10ld", t.seconds[p], 100 * t.seconds[p] / t.wall_s, t.calls[p]);
    return std::string(c);
  };
  for (int p = 0; p < costs::kParts; ++p)
    if (a.costs.on(p) || b.costs.on(p))
      std::printf("  %-13s %34s %34s\n", costs::name(p), cell(a.costs, p).c_str(), cell(b.costs, p).c_str());
  std::printf("  %-13s %11.3f s %22s %11.3f s\n", "wall", a.costs.wall_s, "", b.costs.wall_s);
  int failed = 0;
  for (int p : {costs::CrackFields, costs::Contact, costs::TipParameters})
    if (b.costs.calls[p] != 0 || b.costs.seconds[p] != 0.0) {
      std::printf("FAIL: the uncracked run paid for %s: %ld scopes, %.6f s\n", costs::name(p), b.costs.calls[p],
                  b.costs.seconds[p]);
      failed = 1;
    }
  if (!failed) std::printf("uncracked run: crack fields, contact and J/K: 0 scopes, 0 s (OK)\n");
  return failed;
}

int main(int argc, char** argv) {
  double cell = 0;
  int steps = 2, reps = 0;
  std::string only, which = "dcb", integral = "contour";
  bool null_test = false;  // both models uncracked: the benchmark's own bias and noise
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    bool ok = true;
    if (a == "--cell" && i + 1 < argc) cell = std::atof(argv[++i]);
    else if (a == "--case" && i + 1 < argc) which = argv[++i];
    else if (a == "--steps" && i + 1 < argc) steps = std::atoi(argv[++i]);
    else if (a == "--reps" && i + 1 < argc) reps = std::atoi(argv[++i]);
    else if (a == "--only" && i + 1 < argc) only = argv[++i];
    else if (a == "--null") null_test = true;
    else if (a == "--integral" && i + 1 < argc) integral = argv[++i];
    else ok = false;
    if (!ok || (!only.empty() && only != "cracked" && only != "uncracked" && (only != "evaluation" || which != "fronts")) ||
        (which != "dcb" && which != "rod3d" && which != "fronts" && which != "tips" && which != "costs") ||
        (integral != "contour" && (integral != "domain" || which != "fronts"))) {
      std::fprintf(stderr, "usage: cleave-bench-crack [--case dcb|rod3d|fronts|tips|costs] [--cell MM] [--steps N] [--reps R] [--only cracked|uncracked|evaluation] [--null] [--integral contour|domain]\n");
      return a == "--help" ? 0 : 2;
    }
  }
  if (which == "fronts") {
    nlohmann::json scene = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/rod_elliptical_crack.json");
    scene["resolution"] = cell > 0 ? cell : 3.0;
    if (integral == "domain") scene["crack_tips"].update({{"integral", "domain"}, {"volume_term", true}});
    return bench_fronts(scene, reps > 0 ? reps : 10, only);
  }
  if (which == "rod3d") {  // seed 000 §4.1, its quarter model refined to >= 500 000 particles (3 mm: 480 000)
    nlohmann::json scene = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/rod_elliptical_crack.json");
    scene["resolution"] = cell > 0 ? cell : 2.5;  // mm: 829 440 particles (the grid takes 7.5 / k)
    scene.erase("crack_tips");  // the stepping's cost (J along the front costs at output times only)
    scene["output"].erase("tip_interval");
    return bench<3>("rod (3D, elliptical crack), from 30 us", scene, steps, reps > 0 ? reps : 20, only, null_test,
                    kRodLoadedAt);
  }
  nlohmann::json scene = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/dcb_crack.json");
  if (which == "tips") {
    scene["resolution"] = cell > 0 ? cell : 0.5;
    scene["cracks"][0]["segment_length"] = scene["resolution"];
    return bench_tips(scene, reps > 0 ? reps : 20);
  }
  if (which == "costs") {
    if (cell > 0) scene["resolution"] = cell;
    scene["crack_tips"] = nlohmann::json::object();  // J and K at the tip, at every global.csv row
    return bench_costs(scene);
  }
  scene["resolution"] = cell > 0 ? cell : 0.25;  // the scene's one discretisation key (scene units)
  scene["mpm"]["shape_function"] = "ugimp";
  scene["cracks"][0]["segment_length"] = scene["resolution"];
  return bench<2>("DCB", scene, steps, reps > 0 ? reps : 150, only, null_test);
}

template <int Dim>
int bench(const char* what, const nlohmann::json& scene, int steps, int reps, const std::string& only, bool null_test,
          double loaded_at) {
  if (!only.empty()) {
    Run<Dim> r(scene, only == "cracked", loaded_at);
    for (int i = 0; i < reps; ++i)
      std::printf("rep %d: %s %.1f ns/particle-step\n", i + 1, only.c_str(), r.time(steps).first);
    return 0;
  }
  Run<Dim> cracked(scene, !null_test, loaded_at), uncracked(scene, false, loaded_at);
  std::vector<double> with, without, ratio, cpu_ratio;
  for (int i = 0; i < reps; ++i) {
    std::pair<double, double> a, b;
    if (i % 2 == 0) a = cracked.time(steps), b = uncracked.time(steps);
    else b = uncracked.time(steps), a = cracked.time(steps);
    with.push_back(a.first), without.push_back(b.first), ratio.push_back(a.first / b.first);
    cpu_ratio.push_back(a.second / b.second);
    std::printf("rep %d: cracked %.1f ns/particle-step, uncracked %.1f, ratio %.3f (CPU time %.3f)\n", i + 1, a.first,
                b.first, a.first / b.first, a.second / b.second);
  }
  const double best_with = *std::min_element(with.begin(), with.end()),
               best_without = *std::min_element(without.begin(), without.end());
  std::printf("%s, %zu particles, %d threads, %d steps x %d reps (median): cracked %.1f ns, uncracked %.1f ns, "
              "crack overhead %+.1f %% (per-rep range %+.1f ... %+.1f %%; CPU time %+.1f %%; best blocks %.1f / %.1f ns "
              "= %+.1f %%)\n",
              what, cracked.model.particles.size(), omp_get_max_threads(), steps, reps, median(with), median(without),
              100 * (median(ratio) - 1), 100 * (*std::min_element(ratio.begin(), ratio.end()) - 1),
              100 * (*std::max_element(ratio.begin(), ratio.end()) - 1), 100 * (median(cpu_ratio) - 1), best_with,
              best_without, 100 * (best_with / best_without - 1));
  if (step_timers::kEnabled) {  // where the difference goes, per task (ms per step, median over blocks)
    std::printf("task times, ms per step, median over blocks (cracked / uncracked / difference):\n");
    double sum[2] = {0, 0};
    for (int k = 0; k < step_timers::kSlots; ++k) {
      const double a = 1e3 * median(cracked.task_seconds[k]), b = 1e3 * median(uncracked.task_seconds[k]);
      sum[0] += a, sum[1] += b;
      std::printf("  %-16s %8.3f %8.3f %+8.3f\n", step_timers::name(k), a, b, a - b);
    }
    std::printf("  %-16s %8.3f %8.3f %+8.3f\n", "total timed", sum[0], sum[1], sum[0] - sum[1]);
  }
  return 0;
}
