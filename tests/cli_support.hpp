// Running the built cleave program from a test: its exit code and what it printed, a directory per
// test, a scene that runs at once and one long enough to be stopped. Used by the CLI, run-fault and renderer CLI tests.
#pragma once
#include <sys/wait.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "files.hpp"

namespace cleave::test {

inline const std::string kCleave = CLEAVE_BINARY_DIR "/bin/cleave";

struct Result {
  int code = -1;  // exit status, or 128 + signal when killed (as a shell reports it)
  std::string out, err;
};

// Runs the shell command `PREFIX'cleave' ARGS > OUT 2> ERR` (PREFIX e.g. "cd 'DIR' && ") and reads
// both files back, then removes them.
inline Result run_cleave(const std::string& args, const fs::path& out, const fs::path& err,
                         const std::string& prefix = "") {
  const std::string cmd =
      prefix + "'" + kCleave + "' " + args + " > '" + out.string() + "' 2> '" + err.string() + "'";
  const int status = std::system(cmd.c_str());
  Result r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1;
  r.out = read_text(out);
  r.err = read_text(err);
  fs::remove(out);
  fs::remove(err);
  return r;
}

// The renderer's commands as a machine without a display runs them: DISPLAY unset, the output in
// `dir`.
inline Result run_headless(const std::string& args, const fs::path& dir) {
  return run_cleave(args, dir / "stdout.txt", dir / "stderr.txt", "env -u DISPLAY ");
}

// A test that runs the program in a fresh directory of its own (per_test_path(prefix)); the
// directory is kept when the test fails, to be looked at.
class CliTest : public ::testing::Test {
 protected:
  explicit CliTest(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override {
    dir_ = fresh_dir(per_test_path(prefix_));
    ASSERT_TRUE(fs::exists(kCleave)) << kCleave << " is not built";
  }
  void TearDown() override {
    std::error_code ec;
    if (!HasFailure()) fs::remove_all(dir_, ec);
  }

  fs::path write_scene(const std::string& name, const nlohmann::json& scene) const {
    const fs::path f = dir_ / name;
    std::ofstream(f) << scene.dump(2) << "\n";
    return f;
  }

  fs::path dir_;

 private:
  std::string prefix_;
};

// A 0.1 x 0.05 m steel block in 1 cm cells moving at (1, 0.5) m/s: 200 particles, about three dozen
// steps, 4 frames (t = 0 and every 10 us to 30 us). The CLI tests' scene that runs at once.
inline nlohmann::json tiny_scene() {
  return nlohmann::json::parse(R"({
    "title": "tiny",
    "analysis": {"type": "plane_strain"},
    "resolution": 0.01,
    "materials": [{"name": "steel", "type": "linear_elastic", "E": 2e11, "nu": 0.3, "density": 7800}],
    "bodies": [{"name": "block", "material": "steel", "velocity": [1, 0.5],
                "shape": {"type": "rectangle", "min": [0, 0], "max": [0.1, 0.05]}}],
    "time": {"end": 3e-5},
    "output": {"interval": 1e-5}
  })");
}

// A 0.2 x 0.1 m steel block in 4 mm cells (5000 particles, about 3 steps a microsecond) moving at
// 5 m/s onto a symmetry plane, for `end` seconds with frames every `interval`: a run that takes
// long enough to be stopped.
inline nlohmann::json block_on_symmetry_plane(double end, double interval) {
  nlohmann::json s = nlohmann::json::parse(R"({
    "analysis": {"type": "plane_strain"},
    "grid": {"cell_size": 0.004},
    "materials": [{"name": "steel", "type": "linear_elastic", "E": 2e11, "nu": 0.3, "density": 7800}],
    "bodies": [{"name": "block", "material": "steel", "velocity": [0, -5],
                "shape": {"type": "rectangle", "min": [0, 0], "max": [0.2, 0.1]}}],
    "loads": [{"type": "symmetry", "axis": "y", "position": 0}],
    "output": {"fields": ["displacement", "velocity", "stress"]}
  })");
  s["time"]["end"] = end;
  s["output"]["interval"] = interval;
  return s;
}

}  // namespace cleave::test
