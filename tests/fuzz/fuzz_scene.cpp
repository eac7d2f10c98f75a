// libFuzzer target: the scene reader and the `--set` parser through `cleave check`'s path
// (tests/fuzz/scene_entry.hpp says how the input is split). A SceneError is the expected answer to
// bad input; any other exception, a crash, a hang or a sanitizer report is a finding.
// Build and run: tests/fuzz/CMakeLists.txt (or README.md, build options); figures: docs/validation.md.
#include <omp.h>

#include <cstdio>
#include <cstdlib>
#include <exception>

#include "tests/fuzz/scene_entry.hpp"

namespace {
bool g_verbose = false;  // FUZZ_SCENE_VERBOSE=1: print each input's outcome (replaying inputs by hand)
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  omp_set_num_threads(1);  // one job, one core: the check path has parallel loops
  g_verbose = std::getenv("FUZZ_SCENE_VERBOSE") != nullptr;
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const cleave::fuzz::Input in = cleave::fuzz::split_input(data, size);
  try {
    const auto o = cleave::fuzz::check_scene(in);
    if (g_verbose) {
      if (o.accepted) std::fprintf(stderr, "fuzz_scene: accepted (%zu lines)\n", o.lines.size());
      else std::fprintf(stderr, "fuzz_scene: refused at '%s': %.300s\n", o.key.c_str(), o.reason.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz_scene: not a SceneError: %s\n", e.what());
    std::abort();
  } catch (...) {
    std::fprintf(stderr, "fuzz_scene: not a SceneError: a non-standard exception\n");
    std::abort();
  }
  return 0;
}
