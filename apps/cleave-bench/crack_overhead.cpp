// cleave-bench-crack: the cost of the crack machinery (seed 002 §3.5 reports ~10 %; target <= 5 %).
// The DCB of data/scenes/dcb_crack.json refined to >= 100 000 particles (uGIMP, USAVG), stepped
// with its crack and, alternately in the same process, without it; prints ns per particle-step of
// each and their ratio (median over repetitions). Usage: cleave-bench-crack [--cell MM] [--steps N]
// [--reps R]   (defaults: 0.25 mm cells = 230 400 particles, 40 steps, 5 repetitions).
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "libmpm/scene/scene.hpp"
#include "libmpm/solver/mpm_step.hpp"

using namespace cleave;

namespace {

double time_steps(nlohmann::json scene, bool cracked, int steps, std::size_t& particles) {
  if (!cracked) scene.erase("cracks");
  Model<2> m = build_model<2>(scene);
  particles = m.particles.size();
  auto st = make_stepper<2>(m);
  for (int i = 0; i < 5; ++i) st->step();  // warm-up: first contacts, allocations
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) st->step();
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return 1e9 * s / (double(steps) * double(particles));
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  double cell = 0.25;
  int steps = 40, reps = 5;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--cell" && i + 1 < argc) cell = std::atof(argv[++i]);
    else if (a == "--steps" && i + 1 < argc) steps = std::atoi(argv[++i]);
    else if (a == "--reps" && i + 1 < argc) reps = std::atoi(argv[++i]);
    else {
      std::fprintf(stderr, "usage: cleave-bench-crack [--cell MM] [--steps N] [--reps R]\n");
      return a == "--help" ? 0 : 2;
    }
  }
  nlohmann::json scene = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/dcb_crack.json");
  scene["grid"]["cell_size"] = cell;
  scene["mpm"]["shape_function"] = "ugimp";
  scene["cracks"][0]["segment_length"] = cell;
  std::vector<double> with, without, ratio;
  std::size_t n = 0;
  for (int r = 0; r < reps; ++r) {
    const double a = time_steps(scene, true, steps, n), b = time_steps(scene, false, steps, n);
    with.push_back(a), without.push_back(b), ratio.push_back(a / b);
    std::printf("rep %d: cracked %.1f ns/particle-step, uncracked %.1f, ratio %.3f\n", r + 1, a, b, a / b);
  }
  std::printf("DCB %zu particles, %d threads, %d steps x %d reps (median): cracked %.1f ns, uncracked %.1f ns, "
              "crack overhead %+.1f %%\n",
              n, omp_get_max_threads(), steps, reps, median(with), median(without), 100 * (median(ratio) - 1));
  return 0;
}
