// cleave-bench-output: size and write time of one particle frame of data/scenes/five_disks.json in
// each frame encoding (output.compression none | zlib x output.precision float64 | float32). The
// scene is stepped to mid-run (the disks in contact, stresses everywhere), then the same frame is
// written with write_vtu in the four encodings, in a rotated order each repetition (so a drift of
// the machine's load hits every encoding alike); prints each encoding's file size and its median
// and fastest write time. The write includes building the file, writing it to --dir and syncing it
// to the disk before the rename (io/file_sync.hpp), as a run does.
// Usage: cleave-bench-output [--steps N] [--reps R] [--threads T] [--dir DIR]
// (defaults: 600 steps, 30 repetitions, OpenMP's thread count, /tmp/cleave-bench-output).
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "libmpm/io/vtu_writer.hpp"
#include "libmpm/mpm/mpm_scene.hpp"
#include "libmpm/mpm/mpm_step.hpp"
#include "libmpm/mpm/particle_output.hpp"
#include "libmpm/scene/scene.hpp"

using namespace cleave;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  int steps = 600, reps = 30;
  fs::path dir = "/tmp/cleave-bench-output";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--steps") steps = std::atoi(argv[i + 1]);
    else if (a == "--reps") reps = std::atoi(argv[i + 1]);
    else if (a == "--threads") omp_set_num_threads(std::atoi(argv[i + 1]));
    else if (a == "--dir") dir = argv[i + 1];
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  fs::create_directories(dir);
  Model<2> m = build_model<2>(load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/five_disks.json"));
  auto stepper = make_stepper<2>(m);
  for (int i = 0; i < steps; ++i) stepper->step();
  stepper->sync_strain();  // (the frame holds the strain as a run writes it)
  const io::PointSet ps = particle_point_set<2>(m, m.output.fields);
  std::printf("five_disks.json after %d steps (t = %.3g s): %zu particles, %zu point arrays, %d threads\n", steps,
              stepper->time(), ps.size(), ps.arrays.size(), omp_get_max_threads());

  struct Format {
    const char* name;
    io::VtuFormat format;
    std::vector<double> ms;
    std::uintmax_t bytes = 0;
  };
  std::vector<Format> formats = {{"none float64", {false, false}, {}},
                                 {"zlib float64", {true, false}, {}},
                                 {"none float32", {false, true}, {}},
                                 {"zlib float32", {true, true}, {}}};
  for (auto& f : formats) io::write_vtu(dir / "warm.vtu", ps, f.format);  // warm-up: allocations, page cache
  for (int r = 0; r < reps; ++r)
    for (std::size_t k = 0; k < formats.size(); ++k) {
      Format& f = formats[(k + std::size_t(r)) % formats.size()];
      const fs::path file = dir / "frame.vtu";
      const auto t0 = std::chrono::steady_clock::now();
      io::write_vtu(file, ps, f.format);
      f.ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      f.bytes = fs::file_size(file);
    }
  std::printf("%-13s %10s %8s %10s %10s\n", "encoding", "bytes", "ratio", "median ms", "min ms");
  for (auto& f : formats) {
    std::sort(f.ms.begin(), f.ms.end());
    std::printf("%-13s %10ju %8.3f %10.2f %10.2f\n", f.name, f.bytes, double(f.bytes) / double(formats[0].bytes),
                f.ms[f.ms.size() / 2], f.ms.front());
  }
  fs::remove_all(dir);
  return 0;
}
