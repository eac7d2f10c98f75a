#include "apps/cleave/pd_cli.hpp"

#include <omp.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "apps/cleave/progress.hpp"
#include "libmpm/core/error.hpp"
#include "libmpm/pd/pd_run.hpp"
#include "libmpm/pd/pd_scene.hpp"
#include "libmpm/scene/scene.hpp"

namespace cleave::app {
namespace {

template <int Dim>
int run_dim(const nlohmann::json& scene, const PdCliArgs& a) {
  pd::PdSystem<Dim> m = pd::build_pd_system<Dim>(scene);
  for (const auto& w : m.warnings) std::fprintf(stderr, "cleave: warning: %s\n", w.c_str());
  if (a.command == "check") {
    const auto& k = m.materials[0].k;
    std::printf("scene OK: %s%dD %s, peridynamics: %zu points in %zu bodies, %zu bonds (%zu removed by "
                "pre-cracks)\n",
                m.title.empty() ? "" : (m.title + ": ").c_str(), Dim,
                m.analysis == Analysis::PlaneStress ? "plane stress"
                : m.analysis == Analysis::PlaneStrain ? "plane strain" : "solid",
                m.points.size(), m.bodies.size(), m.bond_count, m.precrack_bonds);
    std::printf("lattice: dx = %.6g m, horizon = %d dx = %.6g m; %s: c = %.6g, s0 = %.6g, implied nu = %.4g\n",
                m.dx, m.horizon_factor, m.delta, m.materials[0].name.c_str(), k.c, k.s0, k.implied_nu);
    std::printf("dt = %.6g s (stable limit, seed 003 eq. 15: %.6g s), %ld steps to %.6g s\n", m.dt, m.stable_dt,
                static_cast<long>(std::ceil(m.end_time / m.dt - 1e-9)), m.end_time);
    std::printf("output: every %.6g s (%zu fields), global.csv every %.6g s, crack_tips.csv every %.6g s "
                "(%zu trackers)\n",
                m.output.interval, m.output.fields.size(), m.output.global_interval, m.output.tip_interval,
                m.trackers.size());
    return 0;
  }
  namespace fs = std::filesystem;
  fs::path out = a.out;
  if (out.empty()) out = fs::path(a.scene).stem().string() + "_out";
  ProgressPrinter printer;
  RunOptions opt;
  opt.out = out;
  opt.resume = a.resume;
  opt.scene_hash = scene_hash(scene);
  opt.progress_interval_s = printer.interval();
  if (!a.quiet) opt.progress = [&](const RunProgress& p) { printer(p); };
  try {
    const RunSummary s = pd::run_pd<Dim>(m, opt);
    printer.finish();
    const double ns = 1e9 * s.wall_s / std::max(1.0, double(s.steps) * double(m.bond_count));
    std::printf("done: %ld steps to t = %.6g s, %zu points, %zu bonds, %d frames, %s wall (%.2f ns/bond-step, "
                "%d threads); output in %s\n",
                s.steps, s.time, m.points.size(), m.bond_count, s.frames, format_seconds(s.wall_s).c_str(), ns,
                omp_get_max_threads(), out.string().c_str());
    return 0;
  } catch (const RunAborted& e) {
    printer.finish();
    std::fprintf(stderr, "cleave: run stopped: %s\nlast state written to %s; %s says \"aborted\"\n", e.what(),
                 out.string().c_str(), (out / "run.json").string().c_str());
    return 3;
  }
}

}  // namespace

int run_peridynamics(const nlohmann::json& scene, const PdCliArgs& a) {
  return scene_dimension(scene) == 3 ? run_dim<3>(scene, a) : run_dim<2>(scene, a);
}

}  // namespace cleave::app
