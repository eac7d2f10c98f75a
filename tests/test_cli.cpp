// The cleave program as a user runs it: exit codes, messages on stderr, what is (and is not)
// written, and resuming. Each test works in its own temporary directory and runs the built binary.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "cli_support.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using cleave::test::kCleave;
using cleave::test::read_text;
using cleave::test::Result;

using cleave::test::tiny_scene;  // 200 particles, about three dozen steps, 4 frames

// The block moves at 2000 m/s in a grid with 2 cells to spare: it leaves within a few dozen steps.
json flyaway_scene() {
  json s = tiny_scene();
  s.erase("resolution");
  s["grid"] = json::parse(R"({"cell_size": 0.01, "min": [-0.02, -0.02], "max": [0.12, 0.07]})");
  s["bodies"][0]["velocity"] = {2000, 0};
  s["time"]["end"] = 1e-4;
  return s;
}

// 5000 particles, about 300 steps, 21 frames: long enough (under a second) to be stopped mid-run.
json longer_scene() { return cleave::test::block_on_symmetry_plane(1e-4, 5e-6); }

// A scene with one bad value: Poisson's ratio 0.7.
json bad_scene() {
  json s = tiny_scene();
  s["materials"][0]["nu"] = 0.7;
  return s;
}

class Cli : public cleave::test::CliTest {
 protected:
  Cli() : CliTest("cleave_cli_") {}

  // Runs `cleave ARGS` in the test directory; stdout and stderr are captured to files.
  Result cleave(const std::string& args) {
    return cleave::test::run_cleave(args, dir_ / "cli_stdout.txt", dir_ / "cli_stderr.txt",
                                    "cd '" + dir_.string() + "' && ");
  }

  // Directories in the test directory (a failed command must create none).
  std::vector<std::string> subdirectories() const {
    std::vector<std::string> d;
    for (const auto& e : fs::directory_iterator(dir_))
      if (e.is_directory()) d.push_back(e.path().filename().string());
    return d;
  }

  json run_json(const std::string& out) const { return json::parse(read_text(dir_ / out / "run.json")); }

  // The (time, file) entries of out/particles.pvd, in order.
  std::vector<std::pair<double, std::string>> pvd_entries(const std::string& out) const {
    std::vector<std::pair<double, std::string>> e;
    const std::string text = read_text(dir_ / out / "particles.pvd");
    const std::regex ds(R"re(timestep="([^"]+)"[^>]*file="([^"]+)")re");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), ds); it != std::sregex_iterator(); ++it)
      e.emplace_back(std::stod((*it)[1].str()), (*it)[2].str());
    return e;
  }
};

// ------------------------------------------------------------------------------------------------
// Bad input: exit 2, a precise message, nothing written

TEST_F(Cli, CheckBadSceneExits2WithKeyPathAndWritesNothing) {
  write_scene("bad.json", bad_scene());
  const Result r = cleave("check bad.json");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("materials[0].nu"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Poisson's ratio must satisfy"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("bad.json"), std::string::npos) << r.err;
  EXPECT_TRUE(subdirectories().empty());
  EXPECT_FALSE(fs::exists(dir_ / "bad_out"));
}

TEST_F(Cli, CheckGoodSceneExits0AndDescribesTheModel) {
  write_scene("tiny.json", tiny_scene());
  const Result r = cleave("check tiny.json");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("scene OK"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("200 particles"), std::string::npos) << r.out;
  EXPECT_TRUE(subdirectories().empty()) << "check must not write anything";
}

TEST_F(Cli, RunBadSceneExits2AndCreatesNoOutputDirectory) {
  write_scene("bad.json", bad_scene());
  const Result r = cleave("run bad.json --out results --quiet");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("materials[0].nu"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "results"));
  EXPECT_TRUE(subdirectories().empty());
  // The default output directory is not created either.
  const Result d = cleave("run bad.json --quiet");
  EXPECT_EQ(d.code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "bad_out"));
}

TEST_F(Cli, MissingSceneFileExits2NamingTheFile) {
  const Result r = cleave("check no_such_scene.json");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("no_such_scene.json"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cannot open"), std::string::npos) << r.err;
  const Result run = cleave("run no_such_scene.json --out results");
  EXPECT_EQ(run.code, 2);
  EXPECT_NE(run.err.find("no_such_scene.json"), std::string::npos) << run.err;
  EXPECT_TRUE(subdirectories().empty());
}

TEST_F(Cli, InvalidJsonExits2) {
  std::ofstream(dir_ / "broken.json") << "{\"analysis\": {\"type\": \"plane_strain\"},\n \"grid\": \n";
  const Result r = cleave("check broken.json");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("broken.json"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("not valid JSON"), std::string::npos) << r.err;
  const Result run = cleave("run broken.json --out results");
  EXPECT_EQ(run.code, 2);
  EXPECT_TRUE(subdirectories().empty());
  // Valid JSON that is not an object.
  std::ofstream(dir_ / "array.json") << "[1, 2, 3]\n";
  EXPECT_EQ(cleave("check array.json").code, 2);
}

TEST_F(Cli, HelpExits0AndMentionsEveryOption) {
  for (const char* flag : {"--help", "-h"}) {
    const Result r = cleave(flag);
    EXPECT_EQ(r.code, 0) << flag;
    for (const char* word : {"--out", "--threads", "--resume", "--quiet", "--help", "--version", "run", "check"})
      EXPECT_NE(r.out.find(word), std::string::npos) << flag << " should mention " << word;
  }
  const Result v = cleave("--version");
  EXPECT_EQ(v.code, 0);
  EXPECT_NE(v.out.find("cleave"), std::string::npos);
}

TEST_F(Cli, BadCommandLinesExit2) {
  write_scene("tiny.json", tiny_scene());
  const Result unknown = cleave("run tiny.json --frobnicate");
  EXPECT_EQ(unknown.code, 2);
  EXPECT_NE(unknown.err.find("--frobnicate"), std::string::npos) << unknown.err;
  EXPECT_NE(unknown.err.find("unknown option"), std::string::npos) << unknown.err;
  EXPECT_EQ(cleave("").code, 2);                         // no command
  EXPECT_EQ(cleave("simulate tiny.json").code, 2);       // unknown command
  EXPECT_EQ(cleave("run").code, 2);                      // no scene
  EXPECT_EQ(cleave("run tiny.json extra.json").code, 2);  // an extra argument
  EXPECT_EQ(cleave("run tiny.json --out").code, 2);       // option without its value
  const Result threads = cleave("run tiny.json --threads zero");
  EXPECT_EQ(threads.code, 2);
  EXPECT_NE(threads.err.find("--threads"), std::string::npos) << threads.err;
  EXPECT_EQ(cleave("run tiny.json --threads 0").code, 2);
  EXPECT_EQ(cleave("run tiny.json --threads 2x").code, 2);
  EXPECT_TRUE(subdirectories().empty()) << "a bad command line writes nothing";
}

// ------------------------------------------------------------------------------------------------
// A complete run

TEST_F(Cli, RunTinySceneWritesEveryOutput) {
  write_scene("tiny.json", tiny_scene());
  const Result r = cleave("run tiny.json --out out --threads 1 --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  const fs::path out = dir_ / "out";
  for (const char* f : {"particles.pvd", "particles_000000.vtu", "global.csv", "run.json", "checkpoint.bin"})
    EXPECT_TRUE(fs::exists(out / f)) << f;

  const std::string csv = read_text(out / "global.csv");
  const std::string header = "time_s,step,kinetic_energy_J,strain_energy_J,external_work_J,total_energy_J,"
                             "momentum_x_kg_m_per_s,momentum_y_kg_m_per_s";  // names with their SI units
  EXPECT_EQ(csv.rfind(header, 0), 0u) << csv.substr(0, 200);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), header) << "a 2D run has exactly these columns";
  EXPECT_GT(std::count(csv.begin(), csv.end(), '\n'), 5);

  const json status = run_json("out");
  EXPECT_EQ(status["status"], "complete");
  EXPECT_GE(status["time"].get<double>(), 3e-5 * (1 - 1e-9));
  EXPECT_GT(status["step"].get<long>(), 10);

  // The summary line on stdout.
  bool done = false;
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);) done = done || line.rfind("done:", 0) == 0;
  EXPECT_TRUE(done) << r.out;
  EXPECT_NE(r.out.find("200 particles"), std::string::npos) << r.out;
  EXPECT_TRUE(r.err.empty()) << "--quiet prints no progress: " << r.err;

  // Every frame in the index exists; frames start at t = 0 and end at the final time.
  const auto frames = pvd_entries("out");
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_EQ(frames.front().first, 0.0);
  EXPECT_EQ(frames.front().second, "particles_000000.vtu");
  EXPECT_DOUBLE_EQ(frames.back().first, status["time"].get<double>());
  for (const auto& [t, f] : frames) EXPECT_TRUE(fs::exists(out / f)) << f;
  EXPECT_NE(read_text(out / "particles_000000.vtu").find("<VTKFile"), std::string::npos);
}

TEST_F(Cli, RunWithDefaultOutputDirectory) {
  write_scene("tiny.json", tiny_scene());
  const Result r = cleave("run tiny.json --threads 1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "tiny_out" / "run.json"));
  EXPECT_EQ(run_json("tiny_out")["status"], "complete");
}

TEST_F(Cli, FreshRunReplacesEarlierOutputs) {
  write_scene("tiny.json", tiny_scene());
  ASSERT_EQ(cleave("run tiny.json --out out --threads 1 --quiet").code, 0);
  ASSERT_TRUE(fs::exists(dir_ / "out" / "particles_000003.vtu"));
  std::ofstream(dir_ / "out" / "notes.txt") << "mine\n";
  json fewer = tiny_scene();
  fewer["output"]["interval"] = 2e-5;  // frames 0, 1 and the final one
  write_scene("tiny.json", fewer);
  ASSERT_EQ(cleave("run tiny.json --out out --threads 1 --quiet").code, 0);
  EXPECT_EQ(pvd_entries("out").size(), 3u);
  EXPECT_FALSE(fs::exists(dir_ / "out" / "particles_000003.vtu")) << "a stale frame of the earlier run is left";
  EXPECT_TRUE(fs::exists(dir_ / "out" / "notes.txt")) << "files that are not cleave outputs are kept";
}

// ------------------------------------------------------------------------------------------------
// A run that stops on a detected problem

TEST_F(Cli, ParticleLeavingTheGridExits3AndWritesTheLastState) {
  write_scene("fly.json", flyaway_scene());
  const Result r = cleave("run fly.json --out out --threads 1 --quiet");
  ASSERT_EQ(r.code, 3) << r.out << r.err;
  const json status = run_json("out");
  EXPECT_EQ(status["status"], "aborted");
  const std::string msg = status["message"].get<std::string>();
  // "step N, time T s: particle P at (x, y) m left the grid"
  const std::regex form(R"(step \d+, time [0-9.e+-]+ s: particle \d+ at \([0-9.e+-]+, [0-9.e+-]+\) m left the grid)");
  EXPECT_TRUE(std::regex_search(msg, form)) << msg;
  EXPECT_NE(r.err.find(msg), std::string::npos) << "stderr repeats the reason: " << r.err;
  EXPECT_NE(r.err.find("aborted"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("done:"), std::string::npos) << r.out;
  // The run stopped long before its end time, after a few dozen steps.
  EXPECT_GT(status["step"].get<long>(), 0);
  EXPECT_LT(status["time"].get<double>(), 5e-5);

  // The last frame is the state at the stop.
  const auto frames = pvd_entries("out");
  ASSERT_GE(frames.size(), 2u);
  EXPECT_DOUBLE_EQ(frames.back().first, status["time"].get<double>());
  EXPECT_TRUE(fs::exists(dir_ / "out" / frames.back().second)) << frames.back().second;
  // global.csv ends with the stopping step.
  const std::string csv = read_text(dir_ / "out" / "global.csv");
  const std::string last = csv.substr(csv.rfind('\n', csv.size() - 2) + 1);
  EXPECT_EQ(std::stod(last.substr(0, last.find(','))), status["time"].get<double>()) << last;
}

// ------------------------------------------------------------------------------------------------
// Resume

TEST_F(Cli, ResumeWithoutCheckpointFailsClearly) {
  write_scene("tiny.json", tiny_scene());
  fs::create_directories(dir_ / "empty");
  const Result r = cleave("run tiny.json --out empty --resume --threads 1 --quiet");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.code, 3);
  EXPECT_NE(r.err.find("checkpoint"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no checkpoint to resume from"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "empty" / "run.json")) << "a failed resume must not claim a status";
}

TEST_F(Cli, ResumeWithADifferentSceneIsRefused) {
  write_scene("tiny.json", tiny_scene());
  ASSERT_EQ(cleave("run tiny.json --out out --threads 1 --quiet").code, 0);
  json other = tiny_scene();
  other["bodies"][0]["velocity"] = {2, 0};
  write_scene("other.json", other);
  const Result r = cleave("run other.json --out out --resume --threads 1 --quiet");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("different scene"), std::string::npos) << r.err;
  EXPECT_EQ(run_json("out")["status"], "complete") << "the earlier run's outputs are untouched";
}

TEST_F(Cli, ResumingACompleteRunFinishesAtOnce) {
  write_scene("tiny.json", tiny_scene());
  ASSERT_EQ(cleave("run tiny.json --out out --threads 1 --quiet").code, 0);
  const auto frames = pvd_entries("out");
  ASSERT_FALSE(frames.empty());
  const std::string last_frame = read_text(dir_ / "out" / frames.back().second);
  const std::string csv = read_text(dir_ / "out" / "global.csv");
  const json before = run_json("out");

  const Result r = cleave("run tiny.json --out out --resume --threads 1 --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("done:", 0), 0u) << r.out;
  const json after = run_json("out");
  EXPECT_EQ(after["status"], "complete");
  EXPECT_EQ(after["step"], before["step"]);
  EXPECT_EQ(after["time"], before["time"]);
  EXPECT_EQ(pvd_entries("out"), frames);
  EXPECT_EQ(read_text(dir_ / "out" / frames.back().second), last_frame);
  EXPECT_EQ(read_text(dir_ / "out" / "global.csv"), csv);
}

TEST_F(Cli, ResumeAfterAKilledRunGivesTheSameResult) {
  write_scene("long.json", longer_scene());
  // Reference: uninterrupted.
  ASSERT_EQ(cleave("run long.json --out ref --threads 1 --quiet").code, 0);

  // Start the same run, kill it hard once a few frames are out.
  const fs::path out = dir_ / "killed";
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    if (::chdir(dir_.c_str()) != 0) ::_exit(127);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execl(kCleave.c_str(), kCleave.c_str(), "run", "long.json", "--out", "killed", "--threads", "1", "--quiet",
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  bool exited = false;
  int status = 0;
  while (!fs::exists(out / "particles_000004.vtu") && std::chrono::steady_clock::now() < deadline) {
    if (::waitpid(pid, &status, WNOHANG) == pid) {
      exited = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  if (!exited) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
  }
  if (run_json("killed")["status"] != "running")
    GTEST_SKIP() << "the run finished before it could be stopped; nothing to resume";
  const auto partial = pvd_entries("killed");
  ASSERT_LT(partial.size(), pvd_entries("ref").size());

  const Result r = cleave("run long.json --out killed --resume --threads 1 --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(run_json("killed")["status"], "complete");
  EXPECT_EQ(run_json("killed")["step"], run_json("ref")["step"]);
  const auto frames = pvd_entries("killed");
  EXPECT_EQ(frames, pvd_entries("ref"));
  ASSERT_FALSE(frames.empty());
  // Bit for bit: the restart holds the full particle state and the step counters.
  EXPECT_TRUE(read_text(out / frames.back().second) == read_text(dir_ / "ref" / frames.back().second))
      << "the final frame differs from the uninterrupted run";
  EXPECT_EQ(read_text(out / "global.csv"), read_text(dir_ / "ref" / "global.csv"));
}

}  // namespace
