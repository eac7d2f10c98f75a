// The scene reader's fuzz entry point, shared by the libFuzzer target (tests/fuzz/fuzz_scene.cpp)
// and the regression suite of the normal build (tests/test_fuzz_regressions.cpp): the code path of
// `cleave check` (parse the text strictly, apply `--set` overrides, build the scene's method in its
// dimension, describe it, estimate the run) without running a step and without writing a file.
//
// Input split: the bytes up to the first "\n--set " are the scene's JSON text; each later
// "\n--set " starts one override, KEY=VALUE, running to the next "\n--set " or the end (one trailing
// '\n' dropped). At most kMaxOverrides overrides are used; the rest of the input is ignored. So a
// scene file with lines "--set resolution=1" appended is a valid input.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace cleave::fuzz {

inline constexpr std::size_t kMaxOverrides = 8;

// "Available memory" seen by the scene's memory check (scene/budget.hpp) while check_scene runs: the
// reader's own refusal path keeps the models it builds small (256 MB: about 3e5 MPM particles or
// 6e4 peridynamic points at the default horizon). Linking the entry point needs
// -Wl,--wrap=_ZN6cleave22available_memory_bytesEv (tests/fuzz/CMakeLists.txt, tests/CMakeLists.txt).
inline constexpr double kMemoryCapBytes = 256e6;

struct Input {
  std::string scene;
  std::vector<std::string> overrides;
};

// Splits fuzzer bytes as described above.
Input split_input(const uint8_t* data, std::size_t size);

struct Outcome {
  bool accepted = false;       // the scene built: `cleave check` would print "scene OK"
  std::string key, reason;     // the SceneError when refused
  std::vector<std::string> lines;  // what `cleave check` prints when accepted
};

// Runs the `cleave check` path on `in` with the memory cap. A SceneError is the expected refusal
// and is returned; any other exception propagates (a finding).
Outcome check_scene(const Input& in);

}  // namespace cleave::fuzz
