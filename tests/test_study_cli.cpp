// cleave study end to end: a resolution study of the photoelastic cracked strip against Feddersen's
// closed form and against its own Richardson extrapolation, what it writes, a second invocation
// that keeps the finished runs, a stopped study that resumes, expectations of the extremes suite, and
// bad studies refused before anything runs.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <thread>

#include "cli_support.hpp"
#include "libmpm/reference/closed_form.hpp"
#include "viz/render/headless.hpp"
#include "viz/render/image.hpp"

namespace cleave::test {
namespace {

using nlohmann::json;

const std::string kStrip = CLEAVE_SOURCE_DIR "/data/scenes/cracked_strip.json";

// Feddersen's K_I of the strip (sigma = 980.665 N / (52 x 5.7 mm^2), a = 8.9 mm, W = 52 mm).
json strip_study(const json& resolutions) {
  return {{"title", "strip"},
          {"scene", kStrip},
          {"vary", {{{"key", "resolution"}, {"values", resolutions}}}},
          {"threads", 2},
          {"quantities",
           {{{"name", "KI"},
             {"column", "KI_Pa_sqrt_m"},
             {"where", {{"tip", 1}}},
             {"reference", {{"closed_form", "centre_crack_KI"},
                            {"values", {{"stress", 980.665 / (52e-3 * 5.7e-3)}, {"half_length", 8.9e-3}, {"width", 52e-3}}}}},
             {"tolerances", {0.05, 0.02}}},
            {{"name", "KI_self"}, {"column", "KI_Pa_sqrt_m"}, {"where", {{"tip", 1}}}, {"reference", {{"finest", true}}}}}}};
}

std::vector<std::map<std::string, std::string>> read_csv(const fs::path& f) {
  std::ifstream in(f);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> head;
  for (std::stringstream ss(line); std::getline(ss, line, ',');) head.push_back(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::map<std::string, std::string> row;
    std::stringstream ss(line);
    std::string cell;
    for (std::size_t c = 0; c < head.size() && std::getline(ss, cell, ','); ++c) row[head[c]] = cell;
    rows.push_back(row);
  }
  return rows;
}

class StudyCli : public CliTest {
 protected:
  StudyCli() : CliTest("study_cli") {}
  fs::path write_study(const std::string& name, const json& study) const {
    const fs::path f = dir_ / name;
    std::ofstream(f) << study.dump(2) << "\n";
    return f;
  }
  Result study(const std::string& args) { return run_cleave("study " + args, dir_ / "o.txt", dir_ / "e.txt", "cd '" + dir_.string() + "' && env -u DISPLAY "); }
};

// Refinement halves the cell twice; the K_I error against Feddersen falls at each step and the 1 mm
// run is within the 2 % the photoelasticity docs record for it (-1.11 %). The study writes its
// table, both diagrams and the summary, with costs for every run.
TEST_F(StudyCli, AResolutionStudyOfTheCrackedStripMeasuresErrorsThatFallWithTheCellAndItsCosts) {
  write_study("s.json", strip_study({4, 2, 1}));
  const Result r = study("s.json --out out");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = read_csv(dir_ / "out" / "study.csv");
  ASSERT_EQ(rows.size(), 3u);
  double last = 1;
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("status"), "complete");
    const double e = std::stod(row.at("KI_error"));
    EXPECT_LT(e, last) << "resolution " << row.at("resolution");
    last = e;
    EXPECT_GT(std::stod(row.at("wall_s")), 0);
    EXPECT_GT(std::stod(row.at("cpu_s")), 0);
    EXPECT_GT(std::stod(row.at("peak_memory_MB")), 1);
    EXPECT_GT(std::stol(row.at("steps")), 10);
  }
  EXPECT_EQ(rows[2].at("particles"), "24960");
  EXPECT_LT(std::stod(rows[2].at("KI_error")), 0.02);
  for (const char* f : {"work_precision.png", "convergence.png", "work_precision_KI_self.png", "summary.md"})
    EXPECT_GT(fs::file_size(dir_ / "out" / f), 1000u) << f;
  const std::string summary = read_text(dir_ / "out" / "summary.md");
  EXPECT_NE(summary.find("within 5 %: cheapest"), std::string::npos) << summary;
  EXPECT_NE(summary.find("centre_crack_KI"), std::string::npos);
  EXPECT_NE(summary.find("observed order"), std::string::npos);

  // Again: every run kept, the same table.
  const std::string before = read_text(dir_ / "out" / "study.csv");
  const Result again = study("s.json --out out");
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_NE(again.err.find("run 3 of 3 (resolution_1): done before, kept"), std::string::npos) << again.err;
  EXPECT_EQ(read_text(dir_ / "out" / "study.csv"), before);
}

// Stopped in its second run, the study exits 130 with the finished run kept; the same command then
// resumes the stopped run from its checkpoint and completes.
TEST_F(StudyCli, AStoppedStudyKeepsItsFinishedRunsAndResumesTheStoppedOne) {
  json scene = block_on_symmetry_plane(5e-3, 5e-4);
  write_scene("block.json", scene);
  const json st = {{"scene", "block.json"}, {"threads", 1},
                   {"vary", {{{"key", "time.end"}, {"values", {2e-5, 5e-3}}}}},
                   {"quantities", {{{"name", "drift"}, {"kind", "energy_drift"}}}}};
  write_study("s.json", st);
  const std::string cmd = "cd '" + dir_.string() + "' && { env -u DISPLAY '" + kCleave +
                          "' study s.json --out out > o.txt 2> e.txt & echo $! > pid.txt; wait; }";
  std::thread t([&] { std::system(cmd.c_str()); });
  const fs::path run_json = dir_ / "out" / "time.end_0.005" / "run.json";
  for (int i = 0; i < 600 && read_text(run_json).find("running") == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));  // a few hundred steps in
  const std::string pid = read_text(dir_ / "pid.txt");
  if (!pid.empty()) ::kill(std::stoi(pid), SIGINT);
  t.join();
  ASSERT_FALSE(pid.empty());
  const json note = json::parse(read_text(dir_ / "out" / "time.end_0.005" / "study_run.json"));
  ASSERT_EQ(note["exit_code"].get<int>(), 130) << read_text(dir_ / "e.txt");
  EXPECT_NE(read_text(dir_ / "e.txt").find("run the same command again"), std::string::npos);
  EXPECT_NE(read_text(dir_ / "out" / "summary.md").find("stopped"), std::string::npos);

  const Result r = study("s.json --out out");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("(time.end_2e-05): done before, kept"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("resumed"), std::string::npos) << r.err;
  const auto rows = read_csv(dir_ / "out" / "study.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].at("status"), "complete");
  EXPECT_NE(read_text(dir_ / "out" / "time.end_0.005" / "stdout.txt").find("resumed at step"), std::string::npos);
}

// The extremes suite's expectations: a step above the stable limit must be refused, a plain run must
// complete with its energy kept; a wrong expectation is reported as missed (exit 3).
TEST_F(StudyCli, ExpectationsOfTheExtremesSuiteAreJudgedAndAMissIsExit3) {
  write_scene("tiny.json", tiny_scene());
  json st = {{"scene", "tiny.json"},
             {"runs", {{{"label", "ok"}, {"expect", {{"outcome", "complete"}, {"energy_drift", 1e-6}}}},
                       {{"label", "too_big_a_step"}, {"set", {{"time.cfl", 1.1}}}, {"expect", {{"outcome", "refuse"}}}}}}};
  write_study("s.json", st);
  Result r = study("s.json --out out");
  ASSERT_EQ(r.code, 0) << r.err;
  auto rows = read_csv(dir_ / "out" / "study.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].at("expectation"), "met");
  EXPECT_EQ(rows[1].at("status"), "refused");
  EXPECT_EQ(rows[1].at("expectation"), "met");

  st["runs"][1]["expect"] = "complete";
  write_study("s.json", st);
  r = study("s.json --out out2");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(read_text(dir_ / "out2" / "summary.md").find("MISSED: expected to complete"), std::string::npos);
}

// Bad studies: exit 2 naming the study key, and no run folder.
TEST_F(StudyCli, ABadStudyIsRefusedNamingItsKeyAndNothingRuns) {
  write_scene("tiny.json", tiny_scene());
  auto refused = [&](const json& st, const std::string& key, const std::string& reason) {
    write_study("bad.json", st);
    fs::remove_all(dir_ / "out");
    const Result r = study("bad.json --out out");
    EXPECT_EQ(r.code, 2) << st.dump();
    EXPECT_NE(r.err.find(key), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(reason), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out" / "study.csv"));
    if (fs::exists(dir_ / "out")) {
      EXPECT_TRUE(fs::is_empty(dir_ / "out")) << "a run started";
    }
  };
  const json drift = {{{"name", "drift"}, {"kind", "energy_drift"}}};
  refused({{"scene", "tiny.json"}, {"vary", {{{"key", "mpm.foo"}, {"values", {1}}}}}, {"quantities", drift}}, "mpm.foo",
          "unknown key");
  refused({{"scene", "tiny.json"}, {"vary", {{{"key", "resolution"}, {"values", json::array()}}}}}, "vary[0].values",
          "empty");
  refused({{"scene", "tiny.json"}, {"vary", {{{"key", "resolution"}, {"values", {0.01}}}}},
           {"quantities", {{{"name", "K"}, {"column", "KI_Pa_sqrt_m"}}}}},
          "quantities[0].file", "no run writes crack_tips.csv");
  refused({{"scene", "tiny.json"}, {"vary", {{{"key", "resolution"}, {"values", {0.01}}}}},
           {"quantities", {{{"name", "E"}, {"file", "global.csv"}, {"column", "kinetic_energy"}}}}},
          "quantities[0].column", "writes no column 'kinetic_energy' in global.csv (it has time_s, step, kinetic_energy_J");
  refused({{"scene", "tiny.json"}, {"vary", {{{"key", "resolution"}, {"values", {0.01}}}}},
           {"quantities", {{{"name", "K"}, {"file", "global.csv"}, {"column", "kinetic_energy_J"},
                            {"reference", {{"closed_form", "centre_crack_KI"}, {"values", {{"stress", 1e6}}}}}}}}},
          "quantities[0].reference.values.half_length", "missing");
  refused({{"scene", "tiny.json"}, {"vary", {{{"key", "resolution"}, {"values", {0.01}}}}},
           {"quantities", {{{"name", "K"}, {"file", "global.csv"}, {"column", "kinetic_energy_J"},
                            {"reference", {{"closed_form", "no_such_form"}}}}}}},
          "quantities[0].reference.closed_form", "unknown closed form 'no_such_form'");
  refused({{"scene", "tiny.json"}, {"vary", {{{"key", "resolution"}, {"values", {0.01}}}}}, {"quantitites", drift}},
          "quantitites", "unknown key");
}

// The Brazilian disk at 1 mm cells against its closed form, once at points (the fringe orders) and
// once through a dark-field photo of the closed form (folded orders, masked to the same circle).
// Folding (the distance to the nearest whole order) can only shrink a difference, so the photo's RMS
// is at most the points' RMS, but for the photo's pixels (0.2 mm) and 8-bit grey levels: 0.02 fringe.
TEST_F(StudyCli, TheBrazilianDiskAgainstAPhotoOfItsClosedFormAgreesAsWellAsAgainstItsPoints) {
  const double R = 0.02, t = 0.005, f = 7000, P = 800, px = 2e-4, r_max = 0.012;
  const int n = 200;
  viz::Image photo{n, n, std::vector<uint8_t>(3 * n * n, 0)}, mask = photo;
  const auto form = reference::make_closed_form("brazilian_disk");
  const auto v = reference::complete_values(*form, {{"force", P}, {"radius", R}, {"thickness", t}});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = -R + (i + 0.5) * px, y = R - (j + 0.5) * px;
      if (x * x + y * y >= R * R) continue;
      const auto s = form->stress(v, x, y);
      const double N = t * std::sqrt((s[0] - s[1]) * (s[0] - s[1]) + 4 * s[2] * s[2]) / f;
      const auto grey = static_cast<uint8_t>(std::lround(255 * std::pow(std::sin(M_PI * N), 2)));
      for (int c = 0; c < 3; ++c) photo.rgb[3 * (j * n + i) + c] = grey;
      if (x * x + y * y < r_max * r_max)
        for (int c = 0; c < 3; ++c) mask.rgb[3 * (j * n + i) + c] = 255;
    }
  viz::write_png(dir_ / "photo.png", photo);
  viz::write_png(dir_ / "mask.png", mask);
  const json common = {{"kind", "fringe_rms"}, {"at", 0.6e-3}, {"fringe_constant", f}, {"thickness", t}};
  json points = common, image = common;
  points["name"] = "points";
  points["reference"] = {{"closed_form", "brazilian_disk"}, {"values", {{"force", P}, {"radius", R}, {"thickness", t}}}};
  points["grid"] = 5e-4, points["radius"] = r_max, points["centre"] = {0, 0};
  image["name"] = "photo";
  image["reference"] = {{"image", "photo.png"}, {"mask", "mask.png"}, {"map", {-R, R, px}}};
  write_study("s.json", {{"scene", CLEAVE_SOURCE_DIR "/data/scenes/brazilian_disk.json"},
                         {"vary", {{{"key", "resolution"}, {"values", {1}}}}},
                         {"quantities", {points, image}}});
  const Result r = study("s.json --out out");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = read_csv(dir_ / "out" / "study.csv");
  ASSERT_EQ(rows.size(), 1u);
  const double by_points = std::stod(rows[0].at("points")), by_photo = std::stod(rows[0].at("photo"));
  EXPECT_GT(by_points, 0);
  EXPECT_LE(by_photo, by_points + 0.02) << "points " << by_points << ", photo " << by_photo;
  // Against a wrong map (the photo shifted by a fifth of the disk) the agreement is worse.
  image["reference"]["map"] = {-R + 0.004, R, px};
  write_study("s.json", {{"scene", CLEAVE_SOURCE_DIR "/data/scenes/brazilian_disk.json"},
                         {"vary", {{{"key", "resolution"}, {"values", {1}}}}},
                         {"quantities", {image}}});
  const Result shifted = study("s.json --out out");
  ASSERT_EQ(shifted.code, 0) << shifted.err;
  EXPECT_GT(std::stod(read_csv(dir_ / "out" / "study.csv")[0].at("photo")), by_photo + 0.05);
}

}  // namespace
}  // namespace cleave::test
