// Runs that meet faults (issue 15): a stop on SIGINT/SIGTERM checkpoints the current step and
// resumes to the files of an uninterrupted run; run.json can be watched while a run goes; a full
// disk or a file size limit is named and leaves the last complete frame and checkpoint; a second
// run into a locked directory is refused naming the first; a checkpoint --resume cannot use is
// refused with exit 2; a resumed complete run says there was nothing to do. The CLI cases run the
// built binary in child processes; no test depends on how fast anything runs (a run that ends
// before the test could interfere is skipped, not failed).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "cli_support.hpp"
#include "libmpm/core/error.hpp"
#include "libmpm/io/file_sync.hpp"
#include "libmpm/io/output_lock.hpp"
#include "libmpm/method/run_scene.hpp"
#include "libmpm/scene/scene.hpp"

namespace cleave {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::fresh_dir;
using test::kCleave;
using test::read_text;
using test::Result;

json read_json(const fs::path& f) { return json::parse(read_text(f)); }

// Every file of a run directory by name, but run.lock (it names the process), and run.json without
// its "costs" (wall-clock times, different in every run).
std::map<std::string, std::string> run_files(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name == "run.lock") continue;
    files[name] = read_text(e.path());
    if (name == "run.json") {
      json status = json::parse(files[name]);
      status.erase("costs");
      files[name] = status.dump();
    }
  }
  return files;
}

// Names differ or contents differ: the first such file, "" when the directories are the same.
std::string first_difference(const fs::path& a, const fs::path& b) {
  const auto fa = run_files(a), fb = run_files(b);
  for (const auto& [name, text] : fa) {
    const auto it = fb.find(name);
    if (it == fb.end()) return name + " (only in " + a.string() + ")";
    if (it->second != text) return name;
  }
  for (const auto& [name, text] : fb)
    if (!fa.count(name)) return name + " (only in " + b.string() + ")";
  return "";
}

bool has_temporaries(const fs::path& dir) {
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".tmp") return true;
  return false;
}

// 5000 particles, about 900 steps, 4 frames: mostly between frames, whenever it is stopped.
json long_scene() { return test::block_on_symmetry_plane(3e-4, 1e-4); }

// 50 particles, about 1000 steps, 11 frames of a few kB, and a global.csv row every step (about
// 150 kB in all): the file that outgrows a 64 kB size limit is global.csv, after a few frames.
json many_rows_scene() {
  return json::parse(R"({
    "analysis": {"type": "plane_strain"},
    "grid": {"cell_size": 0.01},
    "materials": [{"name": "steel", "type": "linear_elastic", "E": 2e11, "nu": 0.3, "density": 7800}],
    "bodies": [{"name": "block", "material": "steel", "velocity": [1, 0.5],
                "shape": {"type": "rectangle", "min": [0, 0], "max": [0.05, 0.03]}}],
    "time": {"end": 1e-3},
    "output": {"interval": 1e-4, "global_interval": 1e-7, "fields": ["displacement", "velocity"]}
  })");
}

class RunFaults : public test::CliTest {
 protected:
  RunFaults() : CliTest("cleave_faults_") {}
  void TearDown() override {
    for (const pid_t pid : children_) {  // a child a failed assertion left running
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
    CliTest::TearDown();
  }

  // Starts `cleave ARGS...` in the test directory, stdout and stderr to files there; a positive
  // fsize_limit sets RLIMIT_FSIZE (bytes per file, as `ulimit -f`) for the child.
  pid_t start(const std::vector<std::string>& args, rlim_t fsize_limit = 0) {
    const pid_t pid = ::fork();
    if (pid == 0) {
      if (::chdir(dir_.c_str()) != 0) ::_exit(127);
      const int out = ::open("child_stdout.txt", O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int err = ::open("child_stderr.txt", O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(out, 1);
      ::dup2(err, 2);
      if (fsize_limit > 0) {
        const rlimit lim{fsize_limit, fsize_limit};
        if (::setrlimit(RLIMIT_FSIZE, &lim) != 0) ::_exit(126);
      }
      std::vector<char*> argv{const_cast<char*>(kCleave.c_str())};
      for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      ::execv(kCleave.c_str(), argv.data());
      ::_exit(127);
    }
    children_.push_back(pid);
    return pid;
  }

  Result finish(pid_t pid) {
    int status = 0;
    ::waitpid(pid, &status, 0);
    std::erase(children_, pid);
    Result r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = read_text(dir_ / "child_stdout.txt");
    r.err = read_text(dir_ / "child_stderr.txt");
    fs::remove(dir_ / "child_stdout.txt");
    fs::remove(dir_ / "child_stderr.txt");
    return r;
  }

  Result cleave(const std::vector<std::string>& args, rlim_t fsize_limit = 0) {
    return finish(start(args, fsize_limit));
  }

  // Waits until `file` exists or the child ends; false when it ended first.
  bool wait_for(pid_t pid, const fs::path& file) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::minutes(5);
    while (!fs::exists(file) && std::chrono::steady_clock::now() < deadline) {
      if (::waitpid(pid, nullptr, WNOHANG) == pid) {
        std::erase(children_, pid);
        return false;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return fs::exists(file);
  }

  std::vector<pid_t> children_;
};

// ------------------------------------------------------------------------------------------------
// Stopping on request

TEST_F(RunFaults, ASigtermWritesACheckpointAtTheCurrentStepAndResumesToTheFilesOfAnUninterruptedRun) {
  write_scene("long.json", long_scene());
  ASSERT_EQ(cleave({"run", "long.json", "--out", "ref", "--threads", "1", "--quiet"}).code, 0);

  const pid_t pid = start({"run", "long.json", "--out", "stopped", "--threads", "1", "--quiet"});
  if (!wait_for(pid, dir_ / "stopped" / "particles_000000.vtu")) GTEST_SKIP() << "the run ended before it was stopped";
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  ::kill(pid, SIGTERM);
  const Result r = finish(pid);
  if (r.code == 0) GTEST_SKIP() << "the run ended before the signal came";
  ASSERT_EQ(r.code, 143) << r.err;

  const json status = read_json(dir_ / "stopped" / "run.json");
  EXPECT_EQ(status["status"], "stopped");
  const long step = status["step"];
  EXPECT_GT(step, 0);
  EXPECT_EQ(status["checkpoint"]["step"], step) << "the checkpoint is at the step the run stopped at";
  EXPECT_EQ(status["checkpoint"]["time"], status["time"]);
  const std::string msg = status["message"];
  EXPECT_NE(msg.find("SIGTERM"), std::string::npos) << msg;
  EXPECT_NE(msg.find("step " + std::to_string(step)), std::string::npos) << msg;
  const std::string resume = status["resume"];
  EXPECT_NE(resume.find("run long.json --out stopped"), std::string::npos) << resume;
  EXPECT_NE(resume.find("--resume"), std::string::npos) << resume;
  EXPECT_NE(r.err.find(resume), std::string::npos) << "stderr says how to resume: " << r.err;
  EXPECT_FALSE(has_temporaries(dir_ / "stopped"));

  // The command run.json gives, as it is, continues to the uninterrupted run's files.
  const int code = std::system(("cd '" + dir_.string() + "' && " + resume + " > resumed.txt 2>&1").c_str());
  const std::string said = read_text(dir_ / "resumed.txt");
  fs::remove(dir_ / "resumed.txt");
  ASSERT_TRUE(WIFEXITED(code) && WEXITSTATUS(code) == 0) << resume << "\n" << said;
  EXPECT_NE(said.find("done: resumed at step " + std::to_string(step) + ", "), std::string::npos) << said;
  EXPECT_EQ(read_json(dir_ / "stopped" / "run.json")["status"], "complete");
  EXPECT_EQ(first_difference(dir_ / "ref", dir_ / "stopped"), "");
}

TEST_F(RunFaults, ASigintStopsTheRunWithExitStatus130AndRunJsonStopped) {
  write_scene("long.json", long_scene());
  const pid_t pid = start({"run", "long.json", "--out", "out", "--threads", "1", "--quiet"});
  if (!wait_for(pid, dir_ / "out" / "particles_000000.vtu")) GTEST_SKIP() << "the run ended before it was stopped";
  ::kill(pid, SIGINT);
  const Result r = finish(pid);
  if (r.code == 0) GTEST_SKIP() << "the run ended before the signal came";
  ASSERT_EQ(r.code, 130) << r.err;
  const json status = read_json(dir_ / "out" / "run.json");
  EXPECT_EQ(status["status"], "stopped");
  EXPECT_NE(status["message"].get<std::string>().find("SIGINT"), std::string::npos) << status.dump();
  EXPECT_EQ(r.out.find("done:"), std::string::npos) << r.out;
}

// The same in process, at a chosen step, for each method's restart state: an MPM run with a crack
// and its tip table, and a peridynamic run with tip trackers.
void stop_and_resume_in_process(const json& scene, long stop_step, const fs::path& dir) {
  fs::remove_all(dir);
  RunOptions ref;
  ref.out = dir / "ref";
  run_scene(scene, {}, ref);

  RunOptions opt;
  opt.out = dir / "stopped";
  opt.progress_interval_s = 0;  // called after every step
  opt.progress = [&](const RunProgress& p) {
    if (p.step == stop_step) std::raise(SIGTERM);
  };
  try {
    run_scene(scene, {}, opt);
    FAIL() << "no stop";
  } catch (const RunStopped& e) {
    EXPECT_EQ(e.signal(), SIGTERM);
  }
  const json status = read_json(opt.out / "run.json");
  EXPECT_EQ(status["status"], "stopped");
  EXPECT_EQ(status["step"], stop_step);
  EXPECT_EQ(status["checkpoint"]["step"], stop_step);

  opt.resume = true;
  opt.progress = nullptr;
  const RunSummary s = run_scene(scene, {}, opt);
  EXPECT_TRUE(s.resumed);
  EXPECT_EQ(s.first_step, stop_step);
  EXPECT_EQ(first_difference(ref.out, opt.out), "");
}

TEST(RunFaultsInProcess, AStopBetweenFramesOfACrackedMpmRunResumesBitForBit) {
  json s = load_scene_file(fs::path(CLEAVE_SOURCE_DIR) / "data/scenes/dcb_crack.json");
  s["time"]["end"] = 0.01;
  s["output"] = {{"interval", 0.004}, {"global_interval", 0.001}, {"tip_interval", 0.001}};
  s["crack_tips"] = json::object();
  stop_and_resume_in_process(s, 7, fs::path(CLEAVE_BINARY_DIR) / "test_run_faults" / "dcb");
}

// A moving 3D crack keeps its triangle lists while it moves less than a margin (spatial_index.hpp);
// the resumed run builds them afresh at the stop: every answer must be the same.
TEST(RunFaultsInProcess, AStopBetweenFramesOfA3DCrackedMpmRunResumesBitForBit) {
  json s = load_scene_file(fs::path(CLEAVE_SOURCE_DIR) / "data/scenes/block_penny_crack.json");
  s["time"]["end"] = 10.0;  // us, 40 steps: the pulse reaches the crack at about 2 us and opens it
  s["output"] = {{"interval", 2.0}, {"global_interval", 0.5}, {"tip_interval", 0.5}};
  s["crack_tips"] = json::object();
  stop_and_resume_in_process(s, 30, fs::path(CLEAVE_BINARY_DIR) / "test_run_faults" / "penny3d");
}

TEST(RunFaultsInProcess, AStopBetweenFramesOfAPeridynamicRunResumesBitForBit) {
  json s = load_scene_file(fs::path(CLEAVE_SOURCE_DIR) / "data/scenes/pd_branching.json");
  s["resolution"] = 2;
  s["time"] = {{"end", 4}, {"dt", 0.2}};
  s["output"] = {{"interval", 2}, {"global_interval", 0.4}, {"tip_interval", 0.4}};
  stop_and_resume_in_process(s, 13, fs::path(CLEAVE_BINARY_DIR) / "test_run_faults" / "pd");
}

// ------------------------------------------------------------------------------------------------
// Watching a run

TEST(RunFaultsInProcess, RunJsonFollowsTheRunWithStepTimeFramesAndEta) {
  const fs::path out = fs::path(CLEAVE_BINARY_DIR) / "test_run_faults" / "watched";
  fs::remove_all(out);
  RunOptions opt;
  opt.out = out;
  opt.status_interval_s = 0;  // every step, so that every step can be checked
  opt.progress_interval_s = 0;
  std::vector<json> seen;
  opt.progress = [&](const RunProgress& p) {
    if (p.time >= p.end_time * (1 - 1e-9)) return;  // the last step's run.json says "complete", after this
    json j = read_json(out / "run.json");
    EXPECT_EQ(j["step"], p.step);
    EXPECT_FALSE(fs::exists(out / "run.json.tmp")) << "written beside and renamed";
    seen.push_back(std::move(j));
  };
  const RunSummary s = run_scene(long_scene(), {"time.end=1e-4", "output.interval=2.5e-5"}, opt);
  ASSERT_GT(seen.size(), 10u);
  for (const json& j : seen) {
    EXPECT_EQ(j["status"], "running");
    for (const char* key : {"time", "frames", "eta_s", "end_time", "pid", "checkpoint"})
      EXPECT_TRUE(j.contains(key)) << key << " missing in " << j.dump();
  }
  EXPECT_GT(seen.back()["frames"].get<long>(), seen.front()["frames"].get<long>());
  EXPECT_GT(seen.back()["time"].get<double>(), seen.front()["time"].get<double>());
  EXPECT_GE(seen.front()["eta_s"].get<double>(), 0.0);
  const json done = read_json(out / "run.json");
  EXPECT_EQ(done["status"], "complete");
  EXPECT_EQ(done["frames"], s.frames);
  EXPECT_FALSE(done.contains("eta_s"));

  // Left to its cadence (here: never by the clock), run.json changes at frames only.
  fs::remove_all(out);
  opt.status_interval_s = 1e9;
  seen.clear();
  long frames_at_step = 1, written_step = 0;  // frame 0 at step 0
  opt.progress = [&](const RunProgress& p) {
    if (p.time >= p.end_time * (1 - 1e-9)) return;  // the last step's run.json says "complete", after this
    const json j = read_json(out / "run.json");
    if (p.frames != frames_at_step) written_step = p.step;  // a frame (and its checkpoint) came at this step
    frames_at_step = p.frames;
    EXPECT_EQ(j["step"], written_step) << "run.json written between frames";
  };
  run_scene(long_scene(), {"time.end=1e-4", "output.interval=2.5e-5"}, opt);
}

// ------------------------------------------------------------------------------------------------
// Write failures

// A power cut cannot be made in a test. What can be checked: the synced writes (io/file_sync.hpp:
// each temporary fsynced before its rename, the checkpoint's directory after it) still leave every
// file whole and no temporary, the checkpoint reads back for a resume, and the sync reports errno.
TEST(RunFaultsInProcess, WritesSyncedBeforeTheirRenameLeaveWholeFilesAndACheckpointThatResumes) {
  const fs::path dir = fresh_dir(fs::path(CLEAVE_BINARY_DIR) / "test_run_faults" / "synced");
  EXPECT_EQ(io::sync_file(dir / "missing"), ENOENT);
  std::ofstream(dir / "a.txt") << "a\n";
  EXPECT_EQ(io::sync_file(dir / "a.txt"), 0);
  io::sync_directory(dir);  // best effort: nothing to report, even for a missing directory
  io::sync_directory(dir / "missing");
  RunOptions opt;
  opt.out = dir / "out";
  const RunSummary s = run_scene(test::tiny_scene(), {}, opt);
  EXPECT_EQ(s.frames, 4);
  EXPECT_FALSE(has_temporaries(opt.out));
  for (const char* f : {"checkpoint.bin", "particles.pvd", "particles_000003.vtu", "run.json", "global.csv"})
    EXPECT_TRUE(fs::exists(opt.out / f)) << f;
  EXPECT_NE(read_text(opt.out / "particles.pvd").find("particles_000003.vtu"), std::string::npos);
  opt.resume = true;
  const RunSummary r = run_scene(test::tiny_scene(), {}, opt);
  EXPECT_TRUE(r.resumed);
  EXPECT_EQ(read_json(opt.out / "run.json")["status"], "complete");
}

TEST_F(RunFaults, AFileSizeLimitIsReportedNotFatalAndTheLastCheckpointResumesToTheSameFiles) {
  write_scene("rows.json", many_rows_scene());
  ASSERT_EQ(cleave({"run", "rows.json", "--out", "ref", "--threads", "1", "--quiet"}).code, 0);
  ASSERT_GT(fs::file_size(dir_ / "ref" / "global.csv"), 100000u) << "the scene no longer outgrows the limit";
  ASSERT_LT(fs::file_size(dir_ / "ref" / "checkpoint.bin"), 60000u);
  ASSERT_LT(fs::file_size(dir_ / "ref" / "particles_000000.vtu"), 60000u);

  // Without SIGXFSZ ignored, the process would die of it here.
  const Result r = cleave({"run", "rows.json", "--out", "out", "--threads", "1", "--quiet"}, 64 * 1024);
  ASSERT_EQ(r.code, 3) << r.out << r.err;
  const json status = read_json(dir_ / "out" / "run.json");
  EXPECT_EQ(status["status"], "aborted");
  const std::string msg = status["message"];
  EXPECT_NE(msg.find("global.csv"), std::string::npos) << msg;
  EXPECT_NE(msg.find("File too large"), std::string::npos) << msg;
  EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
  EXPECT_FALSE(has_temporaries(dir_ / "out"));
  EXPECT_TRUE(status.contains("resume")) << status.dump();
  EXPECT_GT(status["checkpoint"]["step"].get<long>(), 0) << "frames were written before the limit";

  const Result resumed = cleave({"run", "rows.json", "--out", "out", "--threads", "1", "--quiet", "--resume"});
  ASSERT_EQ(resumed.code, 0) << resumed.err;
  EXPECT_EQ(first_difference(dir_ / "ref", dir_ / "out"), "");
}

TEST_F(RunFaults, AFullDiskNamesTheCauseAndTheFileAndKeepsTheLastCompleteFrameAndCheckpoint) {
  write_scene("long.json", long_scene());
  const fs::path out = dir_ / "out";
  const pid_t pid = start({"run", "long.json", "--out", "out", "--threads", "1", "--quiet"});
  if (!wait_for(pid, out / "particles_000000.vtu")) GTEST_SKIP() << "the run ended before the disk could fill";
  // From frame 2 on, every frame is written to /dev/full (writes fail with ENOSPC).
  for (int k = 2; k < 10; ++k) {
    char name[40];
    std::snprintf(name, sizeof name, "particles_%06d.vtu.tmp", k);
    fs::create_symlink("/dev/full", out / name);
  }
  const Result r = finish(pid);
  if (fs::exists(out / "particles_000002.vtu")) GTEST_SKIP() << "frame 2 was written before the disk was full";
  ASSERT_EQ(r.code, 3) << r.out << r.err;
  const json status = read_json(out / "run.json");
  EXPECT_EQ(status["status"], "aborted");
  const std::string msg = status["message"];
  EXPECT_NE(msg.find("No space left on device"), std::string::npos) << msg;
  EXPECT_NE(msg.find("particles_000002.vtu"), std::string::npos) << msg;
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out / "particles_000002.vtu.tmp")) << "the temporary is removed";
  EXPECT_FALSE(has_temporaries(out));
  // Frame 1 and its checkpoint are whole: the index ends with frame 1, and the run resumes.
  for (const auto& e : fs::directory_iterator(out))
    if (fs::is_symlink(e.symlink_status())) fs::remove(e.path());
  EXPECT_NE(read_text(out / "particles.pvd").find("particles_000001.vtu"), std::string::npos);
  EXPECT_EQ(read_text(out / "particles.pvd").find("particles_000002.vtu"), std::string::npos);
  const Result resumed = cleave({"run", "long.json", "--out", "out", "--threads", "1", "--quiet", "--resume"});
  EXPECT_EQ(resumed.code, 0) << resumed.err;
}

// ------------------------------------------------------------------------------------------------
// One run per output directory

TEST(RunFaultsInProcess, TheOutputLockRefusesASecondHolderAndNamesTheFirst) {
  const fs::path dir = fresh_dir(fs::path(CLEAVE_BINARY_DIR) / "test_run_faults" / "lock");
  {
    const io::OutputLock first(dir, "pid 1, started today: cleave run a.json");
    try {
      const io::OutputLock second(dir, "pid 2");
      FAIL() << "a second lock was granted";
    } catch (const RunRefused& e) {
      EXPECT_NE(std::string(e.what()).find("pid 1, started today: cleave run a.json"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("in use"), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(io::OutputLock again(dir, "pid 3")) << "released with its holder";
}

TEST_F(RunFaults, ASecondRunIntoABusyDirectoryExits2NamingTheFirstAndAKilledRunLeavesNoLock) {
  json scene = long_scene();
  scene["time"]["end"] = 3e-2;  // far longer than the test needs: it is killed
  write_scene("long.json", scene);
  const pid_t pid = start({"run", "long.json", "--out", "out", "--threads", "1", "--quiet"});
  ASSERT_TRUE(wait_for(pid, dir_ / "out" / "particles_000000.vtu"));
  const pid_t second = ::fork();
  if (second == 0) {  // not start(): its output files are the first run's
    if (::chdir(dir_.c_str()) != 0) ::_exit(127);
    const int err = ::open("second_stderr.txt", O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(err, 2);
    ::execl(kCleave.c_str(), kCleave.c_str(), "run", "long.json", "--out", "out", "--quiet",
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  ::waitpid(second, &status, 0);
  const std::string err = read_text(dir_ / "second_stderr.txt");
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 2) << err;
  EXPECT_NE(err.find("in use by another cleave run"), std::string::npos) << err;
  EXPECT_NE(err.find("pid " + std::to_string(pid) + ", started "), std::string::npos) << err;
  EXPECT_EQ(read_json(dir_ / "out" / "run.json")["status"], "running") << "the first run's files are untouched";

  ::kill(pid, SIGKILL);
  finish(pid);
  EXPECT_NO_THROW(io::OutputLock(dir_ / "out", "test")) << "the kernel released the killed run's lock";
}

// ------------------------------------------------------------------------------------------------
// Checkpoints --resume cannot use: exit 2 with the reason

TEST_F(RunFaults, ACheckpointOfAnotherMethodDimensionSceneOrFormatIsRefusedWithExit2) {
  json mpm = many_rows_scene();
  mpm["time"]["end"] = 2e-5;
  write_scene("mpm.json", mpm);
  ASSERT_EQ(cleave({"run", "mpm.json", "--out", "out", "--quiet"}).code, 0);
  const std::string checkpoint = read_text(dir_ / "out" / "checkpoint.bin");

  json pd = mpm;
  pd["method"] = "peridynamics";
  pd["analysis"] = {{"type", "plane_stress"}, {"thickness", 0.001}};
  pd.erase("grid");
  pd["resolution"] = 0.01;
  pd["materials"][0]["fracture_energy"] = 1000;
  write_scene("pd.json", pd);
  Result r = cleave({"run", "pd.json", "--out", "out", "--resume", "--quiet"});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("the checkpoint is of a 2D mpm run; the scene is a 2D peridynamics scene"), std::string::npos)
      << r.err;

  json other = mpm;
  other["bodies"][0]["velocity"] = {2, 0};
  write_scene("other.json", other);
  r = cleave({"run", "other.json", "--out", "out", "--resume", "--quiet"});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("written for a different scene"), std::string::npos) << r.err;

  std::string older = checkpoint;
  older[7] = '4';
  std::ofstream(dir_ / "out" / "checkpoint.bin", std::ios::binary) << older;
  r = cleave({"run", "mpm.json", "--out", "out", "--resume", "--quiet"});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("written by an earlier Cleave (checkpoint format 4"), std::string::npos) << r.err;

  std::ofstream(dir_ / "out" / "checkpoint.bin", std::ios::binary) << checkpoint.substr(0, checkpoint.size() / 2);
  r = cleave({"run", "mpm.json", "--out", "out", "--resume", "--quiet"});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("truncated"), std::string::npos) << r.err;

  fs::remove(dir_ / "out" / "checkpoint.bin");
  r = cleave({"run", "mpm.json", "--out", "out", "--resume", "--quiet"});
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("no checkpoint to resume from"), std::string::npos) << r.err;
  EXPECT_EQ(read_json(dir_ / "out" / "run.json")["status"], "complete") << "a refused resume writes nothing";
}

// ------------------------------------------------------------------------------------------------
// What a resumed run reports

TEST_F(RunFaults, ResumingACompleteRunSaysThereIsNothingToDo) {
  write_scene("rows.json", many_rows_scene());
  ASSERT_EQ(cleave({"run", "rows.json", "--out", "out", "--quiet"}).code, 0);
  const long steps = read_json(dir_ / "out" / "run.json")["step"];
  const Result r = cleave({"run", "rows.json", "--out", "out", "--quiet", "--resume"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("nothing to do"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("already complete at step " + std::to_string(steps)), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("ns/"), std::string::npos) << "no speed of zero steps: " << r.out;
}

}  // namespace
}  // namespace cleave
