// Bad input through the cleave program (issue 15): exit 2, a message naming the key and the
// reason, and nothing written; `check` prints the run's estimate; --force is accepted. The reader's
// side of each check is in test_scene_input.cpp.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "libmpm/core/resources.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using cleave::test::Result;

using cleave::test::tiny_scene;  // 200 particles, about three dozen steps, 4 frames

class CliInput : public cleave::test::CliTest {
 protected:
  CliInput() : CliTest("cleave_cli_input_") {}
  void write(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
  // Runs `cleave ARGS` in the test directory, capturing stdout and stderr beside it (a refused run
  // must leave the directory as it was).
  Result cleave(const std::string& args) {
    return cleave::test::run_cleave(args, dir_.string() + ".out", dir_.string() + ".err",
                                    "cd '" + dir_.string() + "' && ");
  }
  // Names in the test directory other than the scenes written there: a refused run writes none.
  std::vector<std::string> written() const {
    std::vector<std::string> n;
    for (const auto& e : fs::directory_iterator(dir_))
      if (e.path().extension() != ".json") n.push_back(e.path().filename().string());
    return n;
  }
};

bool has(const std::string& text, const std::string& word) { return text.find(word) != std::string::npos; }

TEST_F(CliInput, AHugeTimeEndExits2NamingTheKeyAndWritesNothing) {
  json s = tiny_scene();
  s["time"]["end"] = 1e300;
  write("end.json", s.dump());
  for (const char* cmd : {"check end.json", "run end.json --out out --quiet"}) {
    const Result r = cleave(cmd);
    EXPECT_EQ(r.code, 2) << cmd << "\n" << r.err;
    EXPECT_TRUE(has(r.err, "error at 'time.end'")) << r.err;
    EXPECT_FALSE(has(r.err, "-9223372036854775808")) << r.err;
  }
  EXPECT_TRUE(written().empty());
}

TEST_F(CliInput, ANumberBeyondADoubleExits2NamingTheKeyAndTheLine) {
  write("res.json", "{\n  \"analysis\": {\"type\": \"plane_strain\"},\n  \"resolution\": 1e400\n}\n");
  const Result r = cleave("run res.json --out out --quiet");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_TRUE(has(r.err, "res.json: error at 'resolution'")) << r.err;
  EXPECT_TRUE(has(r.err, "line 3, column 17")) << r.err;
  EXPECT_FALSE(has(r.err, "json.exception")) << r.err;
  const Result set = cleave("check res.json --set grid.cell_size=1e400");
  EXPECT_EQ(set.code, 2) << set.err;
  EXPECT_TRUE(written().empty());
}

TEST_F(CliInput, ADirectoryAsTheSceneExits2CannotOpen) {
  fs::create_directories(dir_ / "scenes");
  const Result r = cleave("check scenes");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(r.err, "cleave: cannot open scenes: is a directory\n");
  const Result m = cleave("run missing.json --out out");
  EXPECT_EQ(m.code, 2) << m.err;
  EXPECT_EQ(m.err, "cleave: cannot open missing.json: no such file\n");
  EXPECT_EQ(written(), std::vector<std::string>{"scenes"});
}

TEST_F(CliInput, ADuplicateKeyOrARepeatedSetExits2NamingBoth) {
  std::string text = tiny_scene().dump(2);
  text.insert(text.find("\"time\""), "\"time\": {\"end\": 1},\n  ");
  write("dup.json", text);
  const Result r = cleave("run dup.json --out out --quiet");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_TRUE(has(r.err, "error at 'time': duplicate key")) << r.err;
  write("tiny.json", tiny_scene().dump());
  const Result set = cleave("check tiny.json --set time.end=1e-5 --set time.end=2e-5");
  EXPECT_EQ(set.code, 2) << set.err;
  EXPECT_TRUE(has(set.err, "error at 'time.end': --set twice")) << set.err;
  EXPECT_TRUE(written().empty());
}

TEST_F(CliInput, CheckPrintsTheEstimateOfPointsMemoryAndOutput) {
  write("tiny.json", tiny_scene().dump());
  const Result r = cleave("check tiny.json");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "estimate: 200 points")) << r.out;
  EXPECT_TRUE(has(r.out, "of memory")) << r.out;
  EXPECT_TRUE(has(r.out, "of output: 4 frames x")) << r.out;
  EXPECT_TRUE(has(r.out, "free in tiny_out")) << r.out;
  EXPECT_TRUE(written().empty()) << "check writes nothing";
  // --force is an option of run; the tiny run fits anyway.
  const Result run = cleave("run tiny.json --out out --quiet --force");
  EXPECT_EQ(run.code, 0) << run.err;
}

TEST_F(CliInput, CheckNamesTheOutputEncodingAndCallsTheZlibFigureAnUpperBound) {
  write("tiny.json", tiny_scene().dump());
  const Result raw = cleave("check tiny.json");
  EXPECT_EQ(raw.code, 0) << raw.err;
  EXPECT_TRUE(has(raw.out, "output encoding: raw, float64 (output.compression \"none\", output.precision \"float64\")\n"))
      << raw.out;
  EXPECT_TRUE(has(raw.out, "estimate: about ")) << raw.out;
  const Result packed = cleave("check tiny.json --set output.compression=zlib --set output.precision=float32");
  EXPECT_EQ(packed.code, 0) << packed.err;
  EXPECT_TRUE(has(packed.out, "output encoding: zlib, float32 (output.compression \"zlib\", output.precision \"float32\")"))
      << packed.out;
  EXPECT_TRUE(has(packed.out, "half of float64's")) << packed.out;
  EXPECT_TRUE(has(packed.out, "the output figure is an upper bound: zlib's sizes depend on the data")) << packed.out;
  EXPECT_TRUE(has(packed.out, "estimate: at most ")) << packed.out;
  EXPECT_TRUE(has(packed.out, " of output: 4 frames x")) << packed.out;
  EXPECT_TRUE(written().empty()) << "check writes nothing";
}

TEST_F(CliInput, ASceneNeedingMoreMemoryThanTheMachineHasExits2AtOnce) {
  json s = tiny_scene();
  s["bodies"][0]["shape"]["max"] = {1, 1};
  s["resolution"] = 3.3e-5;  // 3.7e9 particles, 9e8 grid nodes: about 1.8 TB
  if (cleave::available_memory_bytes() > 2e12) GTEST_SKIP() << "this machine has more than 2 TB available";
  write("big.json", s.dump());
  // Refused before allocating: 1.8 TB asked of the allocator would end in std::bad_alloc, not in
  // the budget's message at the resolution key (no wall-time bound: a loaded machine must not fail).
  const Result r = cleave("run big.json --out out --quiet");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_TRUE(has(r.err, "error at 'resolution': needs about")) << r.err;
  EXPECT_TRUE(has(r.err, "of memory")) << r.err;
  EXPECT_TRUE(written().empty());
}

TEST_F(CliInput, AnOutputLargerThanTheFreeDiskExits2AndCheckWarnsOfIt) {
  // A frame at every step of 9e5 steps: 9e5 frames of about 1.2 MB, about 1 TB.
  json s = tiny_scene();
  s["resolution"] = 0.002;  // 5000 particles, dt 1.7e-7 s
  s["time"]["end"] = 0.15;
  s["output"] = {{"interval", 1e-12}, {"global_interval", 1.0}};
  write("many.json", s.dump());
  const Result c = cleave("check many.json --out out");
  ASSERT_EQ(c.code, 0) << c.err;
  if (cleave::free_disk_bytes(dir_) > 900e9) GTEST_SKIP() << "more than 900 GB free here: the run would fit";
  EXPECT_TRUE(has(c.err, "warning: output.interval: the run would write about")) << c.err;
  const Result r = cleave("run many.json --out out --quiet");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_TRUE(has(r.err, "error at 'output.interval'")) << r.err;
  EXPECT_TRUE(has(r.err, "free in out")) << r.err;
  EXPECT_TRUE(written().empty());
}

}  // namespace
