// cleave: the command-line program. `cleave --help` documents every sub-command and option.
#include <omp.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "apps/cleave/pd_cli.hpp"
#include "apps/cleave/progress.hpp"
#include "apps/cleave/render_cli.hpp"
#include "libmpm/core/error.hpp"
#include "libmpm/pd/pd_scene.hpp"
#include "libmpm/scene/scene.hpp"
#include "libmpm/solver/run.hpp"

namespace fs = std::filesystem;
using namespace cleave;

namespace {

constexpr int kOk = 0, kFailure = 1, kBadInput = 2, kAborted = 3;

const char* kHelp = R"(cleave - dynamic fracture with particle methods

Usage:
  cleave run SCENE [--out DIR] [--threads N] [--resume] [--quiet] [--set KEY=VALUE ...]
  cleave check SCENE [--set KEY=VALUE ...]
  cleave render OUT [options]       images and movies (stress colours, photoelastic fringes)
  cleave compare OUT --photo IMG --frame SPEC --map X0,Y0,SCALE[,ANGLE] [--points FILE]
  cleave plot OUT                   energy and J/K plots
  cleave --help | --version         (cleave render --help: the renderer's options)

Commands:
  run     Simulate SCENE (a JSON scene, see docs/scenes.md). Writes into DIR:
            particles.pvd + particles_NNNNNN.vtu   particle time series (VTK XML)
            cracks.pvd + cracks_NNNNNN.vtu         crack paths, surfaces and opening (cracked
                                                   scenes only)
            global.csv                             energies, external work, momentum
            crack_tips.csv                         J1, J2, KI, KII per crack tip (scenes with
                                                   crack_tips)
            checkpoint.bin                         restart state at the last frame
            run.json                               status: running | complete | aborted
          Shows progress (step, simulated time, wall time, ETA) on stderr and a one-line
          summary on stdout.
  check   Validate SCENE without running it: every bad value is reported with its key
          path and reason. Prints what the run would build.

Options:
  --out DIR      output directory (default: SCENE's file name without .json, + "_out")
  --threads N    OpenMP threads (default: OMP_NUM_THREADS or all cores); results are the
                 same for any N
  --resume       continue a stopped run from DIR/checkpoint.bin (same scene)
  --quiet        no progress line
  --set K=V      override one scene value before validation; K is a key path as in error
                 messages (mpm.stress_update, bodies[1].velocity), V is JSON or a plain string:
                 --set mpm.stress_update=USL --set grid.cell_size=1 --set 'time.end=2.5'
  --help         this text
  --version      program version

Exit status: 0 success; 1 I/O or internal error; 2 bad scene or command line (nothing
is written); 3 the run stopped on a detected problem (particle left the grid, NaN,
energy blow-up) after writing its last state; run.json says "aborted" and why.
)";

struct Args {
  std::string command, scene, out;
  int threads = 0;
  bool resume = false, quiet = false;
  std::vector<std::string> sets;
};

// Applies one --set KEY=VALUE to the scene; the key path uses '.' and [i] like error messages.
void apply_set(nlohmann::json& scene, const std::string& kv) {
  const auto eq = kv.find('=');
  if (eq == std::string::npos || eq == 0) throw SceneError(kv, "--set needs KEY=VALUE");
  const std::string key = kv.substr(0, eq), text = kv.substr(eq + 1);
  nlohmann::json value = nlohmann::json::parse(text, nullptr, false);
  if (value.is_discarded()) value = text;  // a bare word such as USL
  nlohmann::json* node = &scene;
  std::size_t i = 0;
  while (i < key.size()) {
    if (key[i] == '[') {
      const auto close = key.find(']', i);
      if (close == std::string::npos) throw SceneError(key, "unclosed '[' in --set key");
      const std::size_t idx = std::stoul(key.substr(i + 1, close - i - 1));
      if (!node->is_array() || idx >= node->size()) throw SceneError(key.substr(0, close + 1), "no such array element");
      node = &(*node)[idx];
      i = close + 1;
    } else {
      if (key[i] == '.') ++i;
      const auto end = key.find_first_of(".[", i);
      const std::string name = key.substr(i, end == std::string::npos ? std::string::npos : end - i);
      if (!node->is_object()) throw SceneError(key, "cannot set a key inside a non-object");
      node = &(*node)[name];
      i = end == std::string::npos ? key.size() : end;
    }
  }
  *node = value;
}

int usage_error(const std::string& msg) {
  std::fprintf(stderr, "cleave: %s\n(see cleave --help)\n", msg.c_str());
  return kBadInput;
}

template <int Dim>
void print_check(const Model<Dim>& m) {
  std::printf("scene OK: %s%dD %s, %zu particles in %zu bodies, %zu materials\n",
              m.title.empty() ? "" : (m.title + ": ").c_str(), Dim,
              m.analysis == Analysis::PlaneStress ? "plane stress"
              : m.analysis == Analysis::PlaneStrain ? "plane strain" : "solid",
              m.particles.size(), m.bodies.size(), m.materials.size());
  std::printf("grid: cell %.6g m, %zu nodes", m.grid.h, m.grid.node_count());
  for (int d = 0; d < Dim; ++d) std::printf("%s%d", d ? " x " : " (", m.grid.nodes[d]);
  std::printf(")\nmethod: %s, %s; dt = %.6g s (stable limit %.6g s), %ld steps to %.6g s\n",
              m.shape_function == ShapeFunctionKind::UGimp ? "uGIMP" : "linear", scheme_name(m.scheme), m.dt,
              m.stable_dt, static_cast<long>(std::ceil(m.end_time / m.dt - 1e-9)), m.end_time);
  if constexpr (Dim == 2)
    for (const auto& c : m.cracks)
      std::printf("crack '%s': %zu segments, contact %s%s, %s detection\n", c.name.c_str(), c.points.size() - 1,
                  crack::contact_law_name(c.contact_law),
                  c.contact_law == crack::Crack2D::ContactLaw::Friction ? (" mu=" + std::to_string(c.friction)).c_str() : "",
                  c.detection == crack::Crack2D::Detection::Volume ? "volume" : "displacement");
  std::printf("output: every %.6g s (%zu fields), global.csv every %.6g s\n", m.output.interval,
              m.output.fields.size(), m.output.global_interval);
  if (m.crack_tips) {
    int tips = 0;
    for (const auto& c : m.cracks) tips += c.tip[0] + c.tip[1];
    const auto& t = *m.crack_tips;
    std::printf("crack tips: %d, J by %s on a %s of %.6g cells (%d points), crack_tips.csv every %.6g s\n", tips,
                t.volume_term ? "eq. 33 (contour + volume)" : "eq. 32 (contour)",
                t.contour == crack::TipSettings::Contour::Circle ? "circle" : "square", t.radius, t.points, t.interval);
  }
}

template <int Dim>
int run_dim(const nlohmann::json& scene, const Args& a) {
  Model<Dim> m = build_model<Dim>(scene);
  for (const auto& w : m.warnings) std::fprintf(stderr, "cleave: warning: %s\n", w.c_str());
  if (a.command == "check") {
    print_check(m);
    return kOk;
  }
  fs::path out = a.out;
  if (out.empty()) out = fs::path(a.scene).stem().string() + "_out";
  app::ProgressPrinter printer;
  RunOptions opt;
  opt.out = out;
  opt.resume = a.resume;
  opt.scene_hash = scene_hash(scene);
  opt.progress_interval_s = printer.interval();
  if (!a.quiet) opt.progress = [&](const RunProgress& p) { printer(p); };
  long warnings = 0;
  opt.log = [&](const std::string& w) {  // the first few in full, then a count at the end
    if (++warnings <= 5) std::fprintf(stderr, "\ncleave: warning: %s\n", w.c_str());
  };
  try {
    const RunSummary s = run_model<Dim>(m, opt);
    printer.finish();
    if (warnings > 5) std::fprintf(stderr, "cleave: %ld warnings in all (5 shown)\n", warnings);
    const double ns = 1e9 * s.wall_s / std::max(1.0, double(s.steps) * m.particles.size());
    std::printf("done: %ld steps to t = %.6g s, %zu particles, %d frames, %s wall (%.0f ns/particle-step, %d threads); "
                "output in %s\n",
                s.steps, s.time, m.particles.size(), s.frames, app::format_seconds(s.wall_s).c_str(), ns,
                omp_get_max_threads(), out.string().c_str());
    return kOk;
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
  Args a;
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
    for (const auto& kv : a.sets) apply_set(scene, kv);
    if (pd::is_peridynamics(scene))  // "method": "peridynamics" (apps/cleave/pd_cli.cpp)
      return app::run_peridynamics(scene, {a.command, a.scene, a.out, a.resume, a.quiet});
    return scene_dimension(scene) == 3 ? run_dim<3>(scene, a) : run_dim<2>(scene, a);
  } catch (const SceneError& e) {
    std::fprintf(stderr, "cleave: %s: error at '%s': %s\n", a.scene.c_str(), e.key_path().c_str(), e.reason().c_str());
    return kBadInput;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cleave: error: %s\n", e.what());
    return kFailure;
  }
}
