// Stability at the extremes (issue 20, docs/validation.md): the fast subset of the suite,
// data/studies/extremes_fast.json, run by the built `cleave study`, with every case's expectation
// met (complete with the energy kept, stop naming the cause, or refused naming the key); and the
// fixes the suite led to, each on its own: peridynamics at the full stable step from rest is no
// "energy blow-up", a crack end half a cell from a free edge (between particle rows) is carried
// through it while one a cell away stays a tip, and points a pre-crack leaves without bonds are
// named. CTest label: extremes (`ctest --test-dir build -L extremes`). No test asserts a wall time.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cli_support.hpp"

namespace cleave::test {
namespace {

using nlohmann::json;

const std::string kStudies = CLEAVE_SOURCE_DIR "/data/studies";

// study.csv: one header line, rows of fields that are quoted ("...", "" for a quote) when they hold
// a comma or a quote.
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& f) {
  std::ifstream in(f);
  auto fields = [](const std::string& line) {
    std::vector<std::string> out;
    std::string cur;
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (quoted) {
        if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') cur += '"', ++i;
        else if (c == '"') quoted = false;
        else cur += c;
      } else if (c == '"') {
        quoted = true;
      } else if (c == ',') {
        out.push_back(cur), cur.clear();
      } else {
        cur += c;
      }
    }
    out.push_back(cur);
    return out;
  };
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> head = fields(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> v = fields(line);
    std::map<std::string, std::string> row;
    for (std::size_t c = 0; c < head.size() && c < v.size(); ++c) row[head[c]] = v[c];
    rows.push_back(row);
  }
  return rows;
}

class Extremes : public CliTest {
 protected:
  Extremes() : CliTest("extremes") {}
  Result cleave(const std::string& args) {
    return run_cleave(args, dir_ / "o.txt", dir_ / "e.txt", "cd '" + dir_.string() + "' && env -u DISPLAY ");
  }
};

// Every case of the fast subset meets its expectation: the study exits 0 and study.csv says "met"
// on each row, one row per run of the file. The kinds of outcome are all there: complete (with the
// drift below its bound), refused (exit 2 naming time.cfl / time.dt) and stopped (exit 3, energy
// blow-up of USL at the stable limit).
TEST_F(Extremes, TheFastSubsetMeetsEveryExpectation) {
  const fs::path study = kStudies + "/extremes_fast.json";
  const json spec = json::parse(read_text(study), nullptr, true, /*ignore_comments=*/true);
  std::set<std::string> labels;
  for (const auto& r : spec["runs"]) labels.insert(r["label"].get<std::string>());
  ASSERT_GE(labels.size(), 10u);

  const Result r = cleave("study '" + study.string() + "' --out out --quiet");
  EXPECT_EQ(r.code, 0) << r.err << r.out;
  const auto rows = read_csv(dir_ / "out" / "study.csv");
  ASSERT_EQ(rows.size(), labels.size());
  std::map<std::string, int> outcomes;
  for (const auto& row : rows) {
    const std::string label = row.at("run");
    EXPECT_TRUE(labels.count(label)) << label;
    EXPECT_EQ(row.at("expectation"), "met") << label << ": " << row.at("status") << ", " << row.at("message");
    ++outcomes[row.at("status")];
    if (row.at("status") == "complete") {
      const double drift = std::stod(row.at("drift"));
      EXPECT_TRUE(std::isfinite(drift)) << label;
    }
  }
  EXPECT_GT(outcomes["complete"], 0);
  EXPECT_GT(outcomes["refused"], 0);
  EXPECT_GT(outcomes["aborted"], 0);
  // The fixes' cases among them: these must complete (before the fixes: an "energy blow-up" at
  // step 1, and the traction work drifting past the 5 % bound).
  for (const auto& row : rows) {
    if (row.at("run") == "pd_cfl_1.0" || row.at("run") == "traction_work_300us") {
      EXPECT_EQ(row.at("status"), "complete") << row.at("run") << ": " << row.at("message");
    }
  }
}

// Peridynamics from rest under a load ramped from zero, at the full stable step with a global row
// every step: velocity-Verlet gives the first step's load its half kick of kinetic energy before
// the work counts any displacement. That is no blow-up (the energy check waits for a reference).
// A cracked plate whose crack contact makes energy (three cracks from one node: +61 % by 40 us; two
// cracks meeting there gained 52 % of the largest energy until they were read as one kinked crack;
// the single crack between node lines that this test used first gained 14 % until contact kept its
// pairs for the whole step, 0.4 % since) is not passed off in silence: cleave run warns and run.json
// records the gain; the same plate with no crack keeps its energy, says nothing and records a gain
// below the 1 % the table asks of it.
TEST_F(Extremes, EnergyMadeByTheNumericsIsReportedAndAPlateThatKeepsItsEnergyIsNot) {
  const std::string plate = "'" + kStudies + "/extremes/cracked_plate.json'";
  const Result gained = cleave("run " + plate + " --out gained --quiet --set 'cracks=[{\"name\": \"a\", \"points\": "
                               "[[0, 0], [-6, 0]]}, {\"name\": \"b\", \"points\": [[0, 0], [3, 6]]}, "
                               "{\"name\": \"c\", \"points\": [[0, 0], [3, -6]]}]'");
  ASSERT_EQ(gained.code, 0) << gained.err;
  EXPECT_NE(gained.err.find("energy not conserved"), std::string::npos) << gained.err;
  const auto g = nlohmann::json::parse(read_text(dir_ / "gained" / "run.json"));
  EXPECT_GT(g["energy_gain"].get<double>(), 0.10);
  const Result kept = cleave("run " + plate + " --out kept --quiet --set cracks=null --set crack_tips=null "
                             "--set output.tip_interval=null");
  ASSERT_EQ(kept.code, 0) << kept.err;
  EXPECT_EQ(kept.err.find("energy not conserved"), std::string::npos) << kept.err;
  EXPECT_LT(nlohmann::json::parse(read_text(dir_ / "kept" / "run.json"))["energy_gain"].get<double>(), 0.01);
}

// Two cracks whose ends coincide are read as the one kinked crack they cut (kept as two, the
// material beyond the kink reached the junction's nodes as two fields that never met, and the plate
// gained 113 % of its energy in 40 us): given either way round, the run is the one-polyline run,
// energy for energy, to roundoff, with the junction no tip (crack_tips.csv: one crack, its two
// outer ends), and check says so. Ends that nearly meet, or three ends at one point, stay apart
// with a warning that says why.
TEST_F(Extremes, TwoCracksMeetingEndToEndRunAsTheOneKinkedCrackTheyCut) {
  const std::string plate = "'" + kStudies + "/extremes/cracked_plate.json'";
  const auto energies = [&](const std::string& out) {
    std::vector<double> e;
    for (const auto& row : read_csv(dir_ / out / "global.csv")) e.push_back(std::stod(row.at("total_energy_J")));
    return e;
  };
  const Result one = cleave("run " + plate + " --out one --quiet --set 'cracks=[{\"name\": \"a\", \"points\": "
                            "[[-6, 0], [0, 0], [3, 6]]}]'");
  ASSERT_EQ(one.code, 0) << one.err;
  EXPECT_EQ(one.err.find("end to end"), std::string::npos) << one.err;
  const std::vector<double> e1 = energies("one");
  ASSERT_GT(e1.size(), 100u);
  for (const char* b : {"[[0, 0], [3, 6]]", "[[3, 6], [0, 0]]"}) {
    const std::string out = b[2] == '0' ? "two" : "two_reversed";
    const Result two = cleave("run " + plate + " --out " + out + " --set 'cracks=[{\"name\": \"a\", \"points\": "
                              "[[-6, 0], [0, 0]]}, {\"name\": \"b\", \"points\": " + b + "}]'");
    ASSERT_EQ(two.code, 0) << two.err;
    EXPECT_NE(two.err.find("cracks 'a' and 'b' meet end to end at (0, 0) m: read as one kinked crack 'a+b'"),
              std::string::npos) << two.err;
    EXPECT_EQ(two.err.find("energy not conserved"), std::string::npos) << two.err;
    EXPECT_EQ(two.err.find("encloses part of crack"), std::string::npos) << two.err;  // no tip at the junction
    const std::vector<double> e2 = energies(out);
    ASSERT_EQ(e2.size(), e1.size()) << out;
    for (std::size_t k = 0; k < e1.size(); ++k) ASSERT_NEAR(e2[k], e1[k], 1e-12 * e1[0]) << out << " row " << k;
    const auto tips = read_csv(dir_ / out / "crack_tips.csv");
    for (const auto& row : tips) EXPECT_EQ(row.at("crack"), "0") << out;  // one crack
    EXPECT_GT(tips.size(), 1u) << out;
  }
  const Result near = cleave("check " + plate + " --set 'cracks=[{\"name\": \"a\", \"points\": [[-6, 0], [0, 0]]}, "
                             "{\"name\": \"b\", \"points\": [[0.5, 0], [3, 6]]}]'");
  EXPECT_EQ(near.code, 0) << near.err;
  EXPECT_NE(near.err.find("cracks 'a' and 'b': the end of one and the start of the other lie 0.5 cell apart"),
            std::string::npos) << near.err;
  EXPECT_NE(near.err.find("only where their ends coincide"), std::string::npos) << near.err;
  const Result three = cleave("check " + plate + " --set 'cracks=[{\"name\": \"a\", \"points\": [[0, 0], [-6, 0]]}, "
                              "{\"name\": \"b\", \"points\": [[0, 0], [3, 6]]}, {\"name\": \"c\", \"points\": "
                              "[[0, 0], [3, -6]]}]'");
  EXPECT_EQ(three.code, 0) << three.err;
  EXPECT_EQ(three.err.find("end to end"), std::string::npos) << three.err;
  EXPECT_NE(three.err.find("cracks 'b' and 'c': the start of one and the start of the other lie 0 cell apart"),
            std::string::npos) << three.err;
}

TEST_F(Extremes, PeridynamicsAtTheFullStableStepFromRestIsNoBlowUp) {
  const Result r = cleave("run '" + kStudies + "/extremes/pd_plate.json' --out pd --quiet --set time.cfl=1 --set time.end=2");
  EXPECT_EQ(r.code, 0) << r.err;
  const json status = json::parse(read_text(dir_ / "pd" / "run.json"));
  EXPECT_EQ(status["status"], "complete") << status.dump();
}

// A crack on a node line (between particle rows, half a particle spacing from each) ending half a
// cell short of a free edge is carried through the edge (rounding decided it before); one ending a
// whole cell short stays a tip.
TEST_F(Extremes, ACrackEndHalfACellFromAnEdgeIsCarriedThroughAndOneACellAwayStays) {
  const std::string plate = "'" + kStudies + "/extremes/cracked_plate.json'";
  const Result half = cleave("check " + plate + " --set 'cracks[0].points=[[-21,0],[19.5,0]]' --set crack_tips=null "
                             "--set output.tip_interval=null");
  EXPECT_EQ(half.code, 0) << half.err;
  EXPECT_NE(half.err.find("its end lies 0.0005 m (0.5 cell) from a free edge"), std::string::npos) << half.err;
  EXPECT_NE(half.err.find("carried on through the edge"), std::string::npos) << half.err;
  const Result cell = cleave("check " + plate + " --set 'cracks[0].points=[[-21,0],[19,0]]'");
  EXPECT_EQ(cell.code, 0) << cell.err;
  EXPECT_EQ(cell.err.find("free edge"), std::string::npos) << cell.err;
}

// A peridynamic pre-crack through a row of points cuts every bond of those points: they are named
// in a warning (they take no force, and their damage reads 0).
TEST_F(Extremes, PointsAPreCrackLeavesWithoutBondsAreNamed) {
  const std::string plate = "'" + kStudies + "/extremes/pd_plate.json'";
  const Result row = cleave("check " + plate + " --set 'cracks[0].points=[[-21,0.25],[21,0.25]]'");
  EXPECT_EQ(row.code, 0) << row.err;
  EXPECT_NE(row.err.find("80 of 3200 points have no bond"), std::string::npos) << row.err;
  const Result between = cleave("check " + plate + " --set 'cracks[0].points=[[-21,0],[21,0]]'");
  EXPECT_EQ(between.code, 0) << between.err;
  EXPECT_EQ(between.err.find("no bond"), std::string::npos) << between.err;
}

}  // namespace
}  // namespace cleave::test
