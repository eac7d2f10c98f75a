// What each part of a run costs (issue 20, "Model only what a scene requires"): run.json's "costs"
// and the `cost:` line of `cleave run` list the parts the scene switched on, and only those. Wall
// times differ from run to run and machine to machine: no test here asserts a time or a share's
// size, only which parts are listed and that they are consistent (cleave-bench-crack --case costs
// asserts that an uncracked scene pays nothing for cracks).
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>

#include "cli_support.hpp"
#include "libmpm/core/error.hpp"
#include "libmpm/method/run_scene.hpp"
#include "libmpm/scene/scene.hpp"

namespace cleave {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The DCB (3600 particles) with J and K at its tip, 87 steps.
json cracked_scene() {
  json s = load_scene_file(fs::path(CLEAVE_SOURCE_DIR) / "data/scenes/dcb_crack.json");
  s["crack_tips"] = json::object();
  s["time"]["end"] = 0.01;
  return s;
}

// The coarse branching plate of peridynamics (1 mm lattice), 20 steps.
json peridynamic_scene() {
  json s = load_scene_file(fs::path(CLEAVE_SOURCE_DIR) / "data/scenes/pd_branching.json");
  s["resolution"] = 1;
  s["time"] = {{"end", 2}, {"dt", 0.1}};
  s["output"]["interval"] = 1;
  return s;
}

class RunCosts : public test::CliTest {
 protected:
  RunCosts() : CliTest("cleave_run_costs_") {}

  // Runs `scene` in process into DIR/out; returns the summary, and run.json in `status`.
  RunSummary run(const json& scene, json& status) {
    RunOptions opt;
    opt.out = dir_ / "out";
    const RunSummary s = run_scene(scene, {}, opt);
    status = json::parse(test::read_text(opt.out / "run.json"));
    return s;
  }
};

// run.json's parts by key; checks that each is a time >= 0 and that together they take at most the
// wall time (up to the rounding of each to seconds).
std::set<std::string> checked_parts(const json& status) {
  std::set<std::string> keys;
  EXPECT_TRUE(status.contains("costs")) << status.dump(2);
  if (!status.contains("costs")) return keys;
  const json& c = status["costs"];
  const double wall = c["wall_s"].get<double>();
  EXPECT_GE(wall, 0.0);
  double sum = 0.0;
  for (const auto& [key, seconds] : c["parts"].items()) {
    keys.insert(key);
    EXPECT_GE(seconds.get<double>(), 0.0) << key;
    sum += seconds.get<double>();
  }
  EXPECT_LE(sum, wall * (1 + 1e-12) + 1e-12) << c.dump(2);
  return keys;
}

TEST_F(RunCosts, ACrackedSceneWithCrackTipsListsStepCrackFieldsContactJKAndOutputInRunJson) {
  json status;
  run(cracked_scene(), status);
  EXPECT_EQ(status["status"], "complete");
  EXPECT_EQ(checked_parts(status), (std::set<std::string>{"step", "crack_fields", "contact", "J_K", "output"}));
}

TEST_F(RunCosts, APlainSceneListsOnlyTheStepAndOutputAndEntersNoCrackPart) {
  json status;
  const RunSummary s = run(test::tiny_scene(), status);
  EXPECT_EQ(checked_parts(status), (std::set<std::string>{"step", "output"}));
  for (int p : {costs::CrackFields, costs::Contact, costs::TipParameters, costs::TipTracking}) {
    EXPECT_EQ(s.costs.calls[p], 0) << costs::name(p);
    EXPECT_EQ(s.costs.seconds[p], 0.0) << costs::name(p);
  }
  EXPECT_EQ(s.costs.calls[costs::Step], s.steps) << "one step scope per step";
}

TEST_F(RunCosts, APeridynamicRunListsStepTipTrackingAndOutput) {
  json status;
  run(peridynamic_scene(), status);
  EXPECT_EQ(checked_parts(status), (std::set<std::string>{"step", "tip_tracking", "output"}));
}

TEST_F(RunCosts, TheSummaryCarriesTheCostsRunJsonRecords) {
  json status;
  const RunSummary s = run(cracked_scene(), status);
  const json& c = status["costs"];
  EXPECT_EQ(c["wall_s"].get<double>(), s.costs.wall_s);
  for (int p = 0; p < costs::kParts; ++p) {
    if (s.costs.on(p)) {
      EXPECT_EQ(c["parts"][costs::key(p)].get<double>(), s.costs.seconds[p]) << costs::name(p);
    }
  }
}

TEST_F(RunCosts, AnAbortedRunRecordsItsCostsInRunJson) {
  json s = test::tiny_scene();  // moving at 2000 m/s with two cells to spare: it leaves the grid
  s.erase("resolution");
  s["grid"] = json::parse(R"({"cell_size": 0.01, "min": [-0.02, -0.02], "max": [0.12, 0.07]})");
  s["bodies"][0]["velocity"] = {2000, 0};
  s["time"]["end"] = 1e-4;
  json status;
  EXPECT_THROW(run(s, status), RunAborted);
  status = json::parse(test::read_text(dir_ / "out" / "run.json"));
  EXPECT_EQ(status["status"], "aborted");
  EXPECT_EQ(checked_parts(status), (std::set<std::string>{"step", "output"}));
}

TEST_F(RunCosts, CleaveRunPrintsTheCostLineAfterTheSummaryEvenWhenQuiet) {
  write_scene("plain.json", test::tiny_scene());
  write_scene("cracked.json", cracked_scene());
  const std::string prefix = "cd '" + dir_.string() + "' && ";
  const auto run_cli = [&](const std::string& args) {
    return test::run_cleave(args, dir_ / "stdout.txt", dir_ / "stderr.txt", prefix);
  };
  const test::Result plain = run_cli("run plain.json --out plain --threads 1 --quiet");
  ASSERT_EQ(plain.code, 0) << plain.err;
  const std::string share = R"([0-9]+\.[0-9] %)";
  EXPECT_TRUE(std::regex_search(plain.out, std::regex("^done: [^\n]*\ncost: step " + share + ", output " + share +
                                                      " of [^\n]* wall\n$")))
      << plain.out;

  const test::Result cracked = run_cli("run cracked.json --out cracked --threads 1 --quiet");
  ASSERT_EQ(cracked.code, 0) << cracked.err;
  EXPECT_TRUE(std::regex_search(cracked.out, std::regex("\ncost: step " + share + ", crack fields " + share +
                                                        ", contact " + share + ", J/K " + share + ", output " +
                                                        share + " of [^\n]* wall\n$")))
      << cracked.out;
}

}  // namespace
}  // namespace cleave
