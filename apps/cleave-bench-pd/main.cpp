// cleave-bench-pd: the same 3D bond-based peridynamic problem in Cleave and in LAMMPS (pair style
// peri/pmb, Debian package `lammps`), one thread each, in one run; prints bond updates per second
// for both and their ratio. A benchmark, not a test (docs/performance.md records its output).
//
// Problem: a cube of n^3 points on a simple cubic lattice of spacing 1 mm, horizon 3 mm, glass
// (E = 65 GPa, rho = 2235 kg/m3, G0 = 204 J/m2; c and s0 of validation.md section 5, 3D), initial
// velocity v_x = 5 m/s * (x / L - 1/2) (the bonds stretch and the block vibrates; no bond breaks
// at this amplitude), velocity-Verlet, `steps` steps of 0.1 us. LAMMPS's neighbour cutoff is set to
// 3.49 mm so that its bond families are exactly Cleave's (pairs closer than horizon + dx/2 =
// 3.5 mm; on this lattice the farthest is sqrt(12) mm = 3.46 mm).
// Bond updates per second = (bonds, each pair counted once) x steps / time of the time-step loop
// (LAMMPS: its "Loop time"; bond-family construction excluded in both).
#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "libmpm/pd/pd_scene.hpp"
#include "libmpm/pd/pd_solver.hpp"

using namespace cleave;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const char* kHelp = R"(cleave-bench-pd - Cleave vs LAMMPS peri/pmb, bond updates per second, one thread

Usage: cleave-bench-pd [--n N] [--steps S] [--lammps PATH] [--no-lammps] [--workdir DIR]
  --n N          points per cube edge (default 30: 27,000 points, ~1.5 million bonds)
  --steps S      time steps (default 200)
  --lammps PATH  LAMMPS binary (default: lmp on PATH; if missing, bench/lammps/setup.sh installs
                 Debian's lammps with apt-get and the benchmark continues)
  --no-lammps    Cleave only
  --workdir DIR  where the LAMMPS input and log go (default ./pd_bench_work)
)";

struct Args {
  int n = 30, steps = 200;
  std::string lammps = "lmp", workdir = "pd_bench_work";
  bool no_lammps = false;
};

json cube_scene(int n, double dx, int steps, double dt) {
  json s;
  s["method"] = "peridynamics";
  s["analysis"] = {{"type", "3d"}};
  s["peridynamics"] = {{"spacing", dx}, {"horizon_factor", 3}};
  s["materials"] = json::array({{{"name", "glass"}, {"type", "linear_elastic"}, {"E", 65e9}, {"density", 2235.0},
                                  {"fracture_energy", 204.0}}});
  const double L = n * dx;
  s["bodies"] = json::array({{{"name", "cube"}, {"material", "glass"},
                              {"shape", {{"type", "box"}, {"min", {0, 0, 0}}, {"max", {L, L, L}}}}}});
  s["time"] = {{"end", steps * dt}, {"dt", dt}};
  return s;
}

bool has_lammps(const std::string& bin) {
  return std::system(("command -v " + bin + " >/dev/null 2>&1").c_str()) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "cleave-bench-pd: %s needs a value\n", s.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (s == "--help" || s == "-h") {
      std::fputs(kHelp, stdout);
      return 0;
    } else if (s == "--n") {
      a.n = std::stoi(next());
    } else if (s == "--steps") {
      a.steps = std::stoi(next());
    } else if (s == "--lammps") {
      a.lammps = next();
    } else if (s == "--no-lammps") {
      a.no_lammps = true;
    } else if (s == "--workdir") {
      a.workdir = next();
    } else {
      std::fprintf(stderr, "cleave-bench-pd: unknown option '%s'\n%s", s.c_str(), kHelp);
      return 2;
    }
  }
  if (a.n < 8 || a.steps < 1) {
    std::fprintf(stderr, "cleave-bench-pd: --n must be >= 8 and --steps >= 1\n");
    return 2;
  }
  const double dx = 1e-3, dt = 1e-7, L = a.n * dx;
  omp_set_num_threads(1);

  // --- Cleave ------------------------------------------------------------------------------------
  auto m = pd::build_pd_system<3>(cube_scene(a.n, dx, a.steps, dt));
  for (std::size_t p = 0; p < m.points.size(); ++p) m.points.v[p][0] = 5.0 * (m.points.x0[p][0] / L - 0.5);
  const auto& k = m.materials[0].k;
  std::printf("problem: %zu points (%d^3, dx = 1 mm), horizon 3 mm, %zu bonds, %d steps of %.3g s "
              "(stable limit %.3g s)\n",
              m.points.size(), a.n, m.bond_count, a.steps, dt, m.stable_dt);
  std::printf("constants: c = %.6g N/m^6, s0 = %.6g (3D, K = 2E/3)\n", k.c, k.s0);
  pd::PdSolver<3> solver(m);
  const auto t0 = std::chrono::steady_clock::now();
  for (int s = 0; s < a.steps; ++s) solver.step();
  const double cleave_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const auto g = solver.global_state();
  const double cleave_rate = double(m.bond_count) * a.steps / cleave_s;
  std::printf("cleave: %.3f s for %d steps, %.4g bond updates/s (1 thread); broken bonds %zu, KE %.4g J, "
              "SE %.4g J\n",
              cleave_s, a.steps, cleave_rate, g.broken, g.kinetic, g.strain);
  if (a.no_lammps) return 0;

  // --- LAMMPS ------------------------------------------------------------------------------------
  if (a.lammps == "lmp" && !has_lammps(a.lammps)) {
    std::printf("lammps: not installed; running bench/lammps/setup.sh (apt-get install lammps)\n");
    const fs::path setup = fs::path(CLEAVE_SOURCE_DIR) / "bench/lammps/setup.sh";
    if (std::system(setup.string().c_str()) != 0 || !has_lammps(a.lammps)) {
      std::fprintf(stderr, "cleave-bench-pd: LAMMPS could not be installed; run %s by hand\n", setup.c_str());
      return 1;
    }
  }
  fs::create_directories(a.workdir);
  const fs::path in = fs::path(a.workdir) / "in.pd_cube", log = fs::path(a.workdir) / "log.pd_cube";
  {
    std::ofstream o(in);
    o.precision(17);
    o << "# written by cleave-bench-pd: the same cube as the Cleave run\n"
      << "units si\nboundary s s s\natom_style peri\natom_modify map array\nneighbor " << 0.5 * dx << " bin\n"
      << "lattice sc " << dx << "\n"
      // Lattice sites k = 0 .. n-1 per axis; Cleave's points are the same sites shifted by dx/2.
      << "region cube block -0.25 " << a.n - 0.75 << " -0.25 " << a.n - 0.75 << " -0.25 " << a.n - 0.75
      << " units lattice\n"
      << "create_box 1 cube\ncreate_atoms 1 region cube\n"
      << "pair_style peri/pmb\n"
      // c, horizon, s00, alpha (alpha = 0: constant critical stretch as in Cleave)
      << "pair_coeff * * " << k.c << " " << 3.49 * dx << " " << k.s0 << " 0.0\n"
      << "set group all density 2235\nset group all volume " << dx * dx * dx << "\n"
      << "variable vx atom 5.0*((x+" << 0.5 * dx << ")/" << L << "-0.5)\n"
      << "velocity all set v_vx 0.0 0.0 units box\n"
      << "fix 1 all nve\ntimestep " << dt << "\nthermo " << a.steps << "\n"
      << "run " << a.steps << "\n";
  }
  const std::string cmd = "OMP_NUM_THREADS=1 " + a.lammps + " -in " + in.string() + " -log " + log.string() +
                          " -screen none";
  std::printf("lammps: %s\n", cmd.c_str());
  if (std::system(cmd.c_str()) != 0) {
    std::fprintf(stderr, "cleave-bench-pd: LAMMPS failed; see %s\n", log.c_str());
    return 1;
  }
  std::ifstream lf(log);
  std::stringstream ss;
  ss << lf.rdbuf();
  const std::string text = ss.str();
  std::smatch mt, ma;
  if (!std::regex_search(text, mt, std::regex(R"(Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms)"))) {
    std::fprintf(stderr, "cleave-bench-pd: no 'Loop time' line in %s\n", log.c_str());
    return 1;
  }
  const double lammps_s = std::stod(mt[1]);
  const long atoms = std::stol(mt[4]);
  if (atoms != static_cast<long>(m.points.size()))
    std::printf("warning: LAMMPS made %ld atoms, Cleave %zu points\n", atoms, m.points.size());
  const double lammps_rate = double(m.bond_count) * a.steps / lammps_s;
  std::string version = "?";
  if (std::regex_search(text, ma, std::regex(R"(LAMMPS \(([^)]*)\))"))) version = ma[1];
  std::printf("lammps (%s, peri/pmb, 1 proc, 1 thread): %.3f s loop time for %d steps, %.4g bond updates/s\n",
              version.c_str(), lammps_s, a.steps, lammps_rate);
  std::printf("ratio cleave / lammps: %.2f (target >= 1.5)\n", cleave_rate / lammps_rate);
  return 0;
}
