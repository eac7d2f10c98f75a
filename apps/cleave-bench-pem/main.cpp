// cleave-bench-pem: the particle equilibrium method (PEM, seed 004) in one run. A benchmark, not a
// test (docs/performance.md records its output).
//
// 1. Pair updates per second of PEM against bond updates per second of peridynamics on the same
//    point count: a 1 m x 0.5 m plane-stress plate, 1 m thick, glass (E = 65 GPa, rho = 2235 kg/m3,
//    G0 = 204 J/m2, pairs and bonds breakable; the run reports that none broke), initial velocity
//    v_x = 0.5 m/s * (x / L - 1/2) (strains ~1e-4), no damping, each model's stable step x 0.9.
//    PEM: unstructured Gmsh triangles at element size h (about N nodes); PD: lattice spacing dx
//    chosen so that its point count matches PEM's particle count, horizon 3 dx. Both built once,
//    then stepped in interleaved blocks of `steps` steps after one warm-up block of each (PEM first
//    in odd repetitions, PD first in even ones, so a drift of the machine's load hits both); per
//    repetition: ns per pair/bond update and per point-step, updates per second, the ratios
//    PEM / PD; then medians and min-max over repetitions. Pairs and bonds are counted once;
//    construction is excluded in both.
// 2. Time to equilibrium of data/scenes/pem_cantilever.json at its 891 particles and at >= 100 000
//    (the same scene at a smaller "resolution", its damping kept): the solver stepped directly, the
//    method's equilibrium test every pem.equilibrium.interval steps (largest speed and relative
//    residual under their tolerances for `checks` checks in a row), under a wall-time cap; wall time,
//    steps, particles and the tip deflection (mean -u_y at x = 8 m) against Timoshenko's 2.082 mm.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "libmpm/pd/pd_scene.hpp"
#include "libmpm/pd/pd_solver.hpp"
#include "libmpm/pem/pem_scene.hpp"
#include "libmpm/pem/pem_solver.hpp"

using namespace cleave;
using nlohmann::json;

namespace {

const char* kHelp = R"(cleave-bench-pem - PEM pair updates vs peridynamic bond updates; cantilever to equilibrium

Usage: cleave-bench-pem [--n N] [--steps S] [--reps R] [--scene PATH] [--cantilever-resolution H]
                        [--cap SECONDS] [--quick]
  --n N            points of the plate of part 1 (default 100000)
  --steps S        steps per block (default 200)
  --reps R         interleaved PEM / PD repetitions (default 5)
  --scene PATH     the cantilever scene (default CLEAVE_SOURCE_DIR/data/scenes/pem_cantilever.json)
  --cantilever-resolution H
                   element size of the large cantilever in m (default 0.0089: >= 100 000 particles)
  --cap SECONDS    wall-time cap of each cantilever run (default 600)
  --quick          skip the large cantilever
)";

struct Args {
  long n = 100000;
  int steps = 200, reps = 5;
  std::string scene = std::string(CLEAVE_SOURCE_DIR) + "/data/scenes/pem_cantilever.json";
  double cantilever_h = 0.0089, cap = 600;
  bool quick = false;
};

constexpr double kLx = 1.0, kLy = 0.5;

json plate_scene(const char* method, double size) {
  json s;
  s["method"] = method;
  s["analysis"] = {{"type", "plane_stress"}, {"thickness", 1}};
  s["resolution"] = size;
  if (std::string(method) == "peridynamics") s["peridynamics"] = {{"horizon_factor", 3}};
  else s["pem"] = {{"elements", "triangles"}};
  s["materials"] = json::array({{{"name", "glass"}, {"type", "linear_elastic"}, {"E", 65e9}, {"density", 2235.0},
                                  {"fracture_energy", 204.0}}});
  s["bodies"] = json::array({{{"name", "plate"}, {"material", "glass"},
                              {"shape", {{"type", "rectangle"}, {"min", {0, 0}}, {"max", {kLx, kLy}}}}}});
  s["time"] = {{"end", 1.0}, {"cfl", 0.9}};
  s["output"] = {{"interval", 1.0}, {"global_interval", 1.0}};
  return s;
}

template <class M>
void set_velocity(M& m) {
  auto& P = m.points;
  for (std::size_t p = 0; p < P.x0.size(); ++p) P.v[p] = Vec<2>(0.5 * (P.x0[p][0] / kLx - 0.5), 0.0);
}

template <class S>
double time_block(S& solver, int steps) {
  const auto t0 = std::chrono::steady_clock::now();
  for (int s = 0; s < steps; ++s) solver.step();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Model building must leave OpenMP's thread count alone (Gmsh changes it; the mesher puts it back):
// checked, so that a regression cannot silently time one thread.
void keep_threads(int threads) {
  if (omp_get_max_threads() == threads) return;
  std::printf("WARNING: building the model changed omp_get_max_threads() from %d to %d; set back to %d\n", threads,
              omp_get_max_threads(), threads);
  omp_set_num_threads(threads);
}

// The machine's load (other processes share the cores of a shared host): /proc/loadavg.
void print_load(const char* when) {
  std::ifstream f("/proc/loadavg");
  std::string a, b, c;
  if (f >> a >> b >> c) std::printf("load average %s: %s %s %s (1, 5, 15 min)\n", when, a.c_str(), b.c_str(),
                                     c.c_str());
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t k = v.size() / 2;
  return v.size() % 2 ? v[k] : 0.5 * (v[k - 1] + v[k]);
}

std::string spread(const std::vector<double>& v, const char* fmt) {
  char lo[64], hi[64], md[64];
  std::snprintf(md, sizeof md, fmt, median(v));
  std::snprintf(lo, sizeof lo, fmt, *std::min_element(v.begin(), v.end()));
  std::snprintf(hi, sizeof hi, fmt, *std::max_element(v.begin(), v.end()));
  return std::string(md) + " (" + lo + " - " + hi + ")";
}

void bench_pairs(const Args& a, int threads) {
  // Unstructured triangles: about 2 / (sqrt(3) h^2) nodes per unit area.
  const double h = std::sqrt(2.0 / std::sqrt(3.0) * kLx * kLy / double(a.n));
  auto t0 = std::chrono::steady_clock::now();
  auto pem = pem::build_pem_system<2>(plate_scene("pem", h));
  const double pem_build = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::size_t np = pem.points.x0.size();
  const double dx = std::sqrt(kLx * kLy / double(np));  // lattice of as many points as PEM has particles
  t0 = std::chrono::steady_clock::now();
  auto pd = pd::build_pd_system<2>(plate_scene("peridynamics", dx));
  const double pd_build = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::size_t nd = pd.points.x0.size();
  set_velocity(pem), set_velocity(pd);
  keep_threads(threads);
  std::printf("\n== 1. PEM pair updates vs peridynamic bond updates (plate %g m x %g m, plane stress, %d threads)\n",
              kLx, kLy, omp_get_max_threads());
  std::printf("PEM: %zu particles (Gmsh unstructured triangles, h = %.4g mm, %zu elements), %zu pairs "
              "(%.2f per particle), dt = %.4g s; built in %.2f s\n",
              np, 1e3 * h, pem.mesh.element_count(), pem.pair_count, double(pem.pair_count) / np, pem.dt, pem_build);
  std::printf("PD:  %zu points (lattice dx = %.4g mm, horizon 3 dx), %zu bonds (%.2f per point), dt = %.4g s; "
              "built in %.2f s; points PD / PEM = %.4f\n",
              nd, 1e3 * dx, pd.bond_count, double(pd.bond_count) / nd, pd.dt, pd_build, double(nd) / np);
  pem::PemSolver<2> ps(pem);
  pd::PdSolver<2> ds(pd);
  time_block(ps, a.steps), time_block(ds, a.steps);  // warm-up block
  std::vector<double> pem_ns, pd_ns, pem_pt, pd_pt, ratio_upd, ratio_pt;
  std::printf("%d repetitions of %d steps each (PEM first in odd repetitions, PD first in even ones):\n", a.reps,
              a.steps);
  std::printf("  rep | PEM ns/pair-update  pair-updates/s | PD ns/bond-update  bond-updates/s | PEM ns/pt-step  "
              "PD ns/pt-step | PEM/PD per update  per point-step\n");
  for (int r = 0; r < a.reps; ++r) {
    double tp, td;
    if (r % 2 == 0) tp = time_block(ps, a.steps), td = time_block(ds, a.steps);
    else td = time_block(ds, a.steps), tp = time_block(ps, a.steps);
    const double up = 1e9 * tp / (double(pem.pair_count) * a.steps), ud = 1e9 * td / (double(pd.bond_count) * a.steps);
    const double qp = 1e9 * tp / (double(np) * a.steps), qd = 1e9 * td / (double(nd) * a.steps);
    pem_ns.push_back(up), pd_ns.push_back(ud), pem_pt.push_back(qp), pd_pt.push_back(qd);
    ratio_upd.push_back(up / ud), ratio_pt.push_back(qp / qd);
    std::printf("  %3d | %18.3f  %14.4g | %17.3f  %14.4g | %14.2f  %13.2f | %17.3f  %14.3f\n", r + 1, up, 1e9 / up,
                ud, 1e9 / ud, qp, qd, up / ud, qp / qd);
  }
  std::vector<double> pem_rate, pd_rate;
  for (double x : pem_ns) pem_rate.push_back(1e9 / x);
  for (double x : pd_ns) pd_rate.push_back(1e9 / x);
  std::printf("median (min - max) over %d repetitions:\n", a.reps);
  std::printf("  PEM: %s ns per pair-update, %s pair-updates/s, %s ns per particle-step\n",
              spread(pem_ns, "%.3f").c_str(), spread(pem_rate, "%.4g").c_str(), spread(pem_pt, "%.2f").c_str());
  std::printf("  PD:  %s ns per bond-update, %s bond-updates/s, %s ns per point-step\n",
              spread(pd_ns, "%.3f").c_str(), spread(pd_rate, "%.4g").c_str(), spread(pd_pt, "%.2f").c_str());
  std::printf("  ratio PEM / PD (per repetition): time per update %s, time per point-step %s\n",
              spread(ratio_upd, "%.3f").c_str(), spread(ratio_pt, "%.3f").c_str());
  const auto gp = ps.global_state();
  const auto gd = ds.global_state();
  std::printf("  after %ld PEM / %ld PD steps (warm-up included): broken pairs %zu, broken bonds %zu, halved PEM steps "
              "%ld; KE + SE: PEM %.4g J, PD %.4g J\n",
              ps.step_count(), ds.step_count(), gp.broken, gd.broken, ps.halved_steps(), gp.total(), gd.total());
}

// Runs the cantilever to equilibrium (or the wall-time cap) and prints where it ended; returns the
// simulated time to equilibrium (0: not reached). `t_ref` > 0: the small run's, for an extrapolation.
double cantilever(json scene, double resolution, double cap, int threads, double t_ref) {
  if (resolution > 0) scene["resolution"] = resolution;
  auto t0 = std::chrono::steady_clock::now();
  auto m = pem::build_pem_system<2>(scene);
  const double build = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  keep_threads(threads);
  const auto& P = m.points;
  const auto& eq = m.equilibrium;
  std::printf("cantilever at resolution %g m: %zu particles, %zu pairs, dt = %.4g s, damping %g 1/s; built in %.2f s\n",
              double(scene["resolution"]), P.x0.size(), m.pair_count, m.dt, m.damping, build);
  if (!eq.enabled) {
    std::printf("  the scene has no pem.equilibrium: nothing to run\n");
    return 0;
  }
  pem::PemSolver<2> s(m);
  int calm = 0;
  bool done = false;
  pem::PemGlobal<2> g;
  t0 = std::chrono::steady_clock::now();
  double wall = 0;
  while (!done && wall < cap) {
    s.step();
    if (s.step_count() % eq.interval) continue;
    g = s.global_state();
    if (g.max_speed < eq.velocity && g.relative_residual < eq.residual) done = ++calm >= eq.checks;
    else calm = 0;
    wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  double tip = 0, count = 0, tol = 1e-6 * m.mesh_size;
  for (std::size_t p = 0; p < P.x0.size(); ++p)
    if (std::fabs(P.x0[p][0] - 8.0) < tol) tip += -P.u[p][1], ++count;
  tip /= std::max(count, 1.0);
  // Timoshenko (kappa = 5/6, G = 3E/8, the network's nu = 1/3): q L^4 / (8 E I) + q L^2 / (2 kappa G A).
  const double E = 3e10, q = 1e4, L = 8, I = 1.0 / 12, G = 3 * E / 8;
  const double timo = q * std::pow(L, 4) / (8 * E * I) + q * L * L / (2 * (5.0 / 6) * G * 1.0);
  std::printf("  %s after %.1f s wall, %ld steps (%.4g s simulated, %.3g us per particle-step incl. checks): largest "
              "speed %.3g m/s (tol %.3g), relative residual %.3g (tol %.3g), %d calm checks in a row (need %d)\n",
              done ? "EQUILIBRIUM" : "CAP HIT, NOT at equilibrium", wall, s.step_count(), s.time(),
              1e6 * wall / (double(P.x0.size()) * std::max(1L, s.step_count())), g.max_speed, eq.velocity,
              g.relative_residual, eq.residual, calm, eq.checks);
  std::printf("  tip deflection (mean -u_y of the %.0f particles at x = 8 m): %.4f mm; Timoshenko %.4f mm; "
              "ratio %.4f\n",
              count, 1e3 * tip, 1e3 * timo, tip / timo);
  if (!done && t_ref > 0 && s.step_count() > 0)
    std::printf("  extrapolation, not a measurement: if it needs the small run's %.3g s simulated (the damping is set "
                "for the first mode), ~%.3g steps, ~%.0f s wall at this rate\n",
                t_ref, t_ref / m.dt, wall * t_ref / s.time());
  return done ? s.time() : 0.0;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // a capped run's progress shows as it goes
  std::string cmdline = argv[0];
  for (int i = 1; i < argc; ++i) cmdline += std::string(" ") + argv[i];
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "cleave-bench-pem: %s needs a value\n", s.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (s == "--help" || s == "-h") {
      std::fputs(kHelp, stdout);
      return 0;
    } else if (s == "--n") {
      a.n = std::stol(next());
    } else if (s == "--steps") {
      a.steps = std::stoi(next());
    } else if (s == "--reps") {
      a.reps = std::stoi(next());
    } else if (s == "--scene") {
      a.scene = next();
    } else if (s == "--cantilever-resolution") {
      a.cantilever_h = std::stod(next());
    } else if (s == "--cap") {
      a.cap = std::stod(next());
    } else if (s == "--quick") {
      a.quick = true;
    } else {
      std::fprintf(stderr, "cleave-bench-pem: unknown option '%s'\n%s", s.c_str(), kHelp);
      return 2;
    }
  }
  if (a.n < 100 || a.steps < 1 || a.reps < 1 || !(a.cap > 0) || !(a.cantilever_h > 0)) {
    std::fprintf(stderr, "cleave-bench-pem: --n must be >= 100, --steps, --reps >= 1, --cap and "
                         "--cantilever-resolution > 0\n");
    return 2;
  }
  std::printf("command: %s\n", cmdline.c_str());
  const int threads = omp_get_max_threads();
  std::printf("threads: %d (omp_get_max_threads)\n", threads);
  print_load("at the start");
  try {
    bench_pairs(a, threads);
    std::ifstream f(a.scene);
    if (!f) {
      std::fprintf(stderr, "cleave-bench-pem: cannot read %s\n", a.scene.c_str());
      return 1;
    }
    const json scene = json::parse(f);
    print_load("after part 1");
    std::printf("\n== 2. Cantilever to equilibrium (%s), wall-time cap %g s per run\n", a.scene.c_str(), a.cap);
    const double t_small = cantilever(scene, 0, a.cap, threads, 0);
    if (a.quick) std::printf("large cantilever skipped (--quick)\n");
    else cantilever(scene, a.cantilever_h, a.cap, threads, t_small);
    print_load("at the end");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cleave-bench-pem: %s\n", e.what());
    return 1;
  }
  return 0;
}
