// Static solves by dynamic relaxation (scene key "static", method/relaxation.hpp): the relaxation on
// a spring, and the cracked strip and the DCB against their long damped runs (issue 21: within
// 0.5 % in J and K).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "cli_support.hpp"
#include "libmpm/method/relaxation.hpp"

using namespace cleave;
using namespace cleave::test;

TEST(Relaxation, ASpringUnderADeadLoadRelaxesToItsStaticDeflectionWithinHalfTheTolerance) {
  // m x'' = F - k x - kappa m x', omega = 10 rad/s, static deflection F / k = 0.01.
  const double m = 1, k = 100, F = 1, dt = 0.01, tol = 1e-4;
  Relaxation r(tol);
  double x = 0, v = 0, t = 0, kappa = 0;
  long step = 0;
  for (; step < 100000 && !r.reached(); ++step) {
    v += dt * ((F - k * x) / m - kappa * v);
    x += dt * v, t += dt;
    if (r.due(step + 1)) kappa = r.check(t, 0.5 * k * x * x, 0.5 * m * v * v, m * x * x);
  }
  ASSERT_TRUE(r.reached()) << r.state();
  EXPECT_NEAR(r.omega(), 10.0, 1e-9);  // the quotient of a one-mode system is its frequency
  EXPECT_NEAR(r.kappa(), 2 * Relaxation::kDampingRatio * 10.0, 1e-9);
  EXPECT_NEAR(x, 0.01, 0.5 * tol * 0.01) << "at t = " << t;
  EXPECT_LT(t, 3.0) << "about 20 / omega";  // critical-like damping, not a creep
}

TEST(Relaxation, AnUndampedSwingIsNeverStaticThoughItsEnergyRepeatsEveryPeriod) {
  // x = 0.01 (1 - cos w t): a spring released under a dead load with no damping at all; U and K come
  // back every period, and checks a whole period apart would see the same state.
  Relaxation r(1e-4);
  const double w = 10;
  for (int i = 1; i <= 5000; ++i) {
    const double t = 0.001 * i, x = 0.01 * (1 - std::cos(w * t)), v = 0.01 * w * std::sin(w * t);
    r.check(t, 0.5 * w * w * x * x, 0.5 * v * v, x * x);
    ASSERT_FALSE(r.reached()) << "t = " << t << ": " << r.state();
  }
}

namespace {
class StaticRun : public CliTest {
 protected:
  StaticRun() : CliTest("test_static_relaxation") {}
  // The last row's value of `column` for crack 0's tip `tip` in OUT/crack_tips.csv.
  static double last_tip_value(const fs::path& out, const std::string& column, int tip) {
    std::ifstream in(out / "crack_tips.csv");
    std::string line;
    std::getline(in, line);
    std::vector<std::string> head;
    for (std::stringstream ss(line); std::getline(ss, line, ',');) head.push_back(line);
    const auto c = std::size_t(std::find(head.begin(), head.end(), column) - head.begin());
    const auto ct = std::size_t(std::find(head.begin(), head.end(), "tip") - head.begin());
    double v = NAN;
    while (std::getline(in, line)) {
      std::vector<double> row;
      for (std::stringstream ss(line); std::getline(ss, line, ',');) row.push_back(std::strtod(line.c_str(), nullptr));
      if (row.size() > c && int(row[ct]) == tip) v = row[c];
    }
    return v;
  }
  Result run(const std::string& scene, const std::string& out, const std::string& sets) {
    return run_cleave("run '" CLEAVE_SOURCE_DIR "/data/scenes/" + scene + "' --quiet --out '" + (dir_ / out).string() +
                          "' " + sets, dir_ / "o.txt", dir_ / "e.txt");
  }
};
}  // namespace

TEST_F(StaticRun, TheCrackedStripRelaxedToStaticGivesTheKIOfItsLongDampedRunWithinHalfAPercent) {
  // The long damped run: the same step load, kinetic damping 68 /ms (critical for the stretching
  // mode, measured), at the dynamic default CFL 0.5, to 1.5 ms (about 50 / omega).
  auto r = run("cracked_strip.json", "static", "");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto status = nlohmann::json::parse(read_text(dir_ / "static" / "run.json"));
  EXPECT_EQ(status["status"], "complete");
  EXPECT_TRUE(status["static"]["reached"].get<bool>());
  EXPECT_LT(status["time"].get<double>(), 1e-3) << "static well before time.end (3 ms)";
  r = run("cracked_strip.json", "damped", "--set static=null --set damping.kinetic=68 --set time.end=1.5 --set time.cfl=0.5");
  ASSERT_EQ(r.code, 0) << r.err;
  for (int tip : {0, 1}) {
    const double ks = last_tip_value(dir_ / "static", "KI_Pa_sqrt_m", tip);
    const double kd = last_tip_value(dir_ / "damped", "KI_Pa_sqrt_m", tip);
    EXPECT_NEAR(ks / kd, 1.0, 0.005) << "static " << ks << ", damped " << kd;
    EXPECT_NEAR(ks / kd, 1.0, 1e-4) << "4 digits: static " << ks << ", damped " << kd;  // tolerance 1e-4 on U
    // Feddersen: sigma sqrt(pi a) sqrt(sec(pi a / W)), 1 mm cells read 1.1 % low (docs/photoelasticity.md).
    EXPECT_NEAR(ks / 0.596957e6, 1.0, 0.02);
  }
}

TEST_F(StaticRun, TheDcbRelaxedToStaticGivesTheJOfItsLongDampedRunWithinHalfAPercent) {
  const std::string tips = "--set 'crack_tips={\"contour\": \"circle\", \"radius\": 2}'";
  auto r = run("dcb_crack.json", "damped", tips);  // as the scene is: ramp over 0.05 s, kinetic damping, 0.4 s
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("dcb_crack.json", "static", tips + " --set damping=null --set 'static={}' --set time.end=2");
  ASSERT_EQ(r.code, 0) << r.err;
  const double js = last_tip_value(dir_ / "static", "J1_J_per_m2", 1), jd = last_tip_value(dir_ / "damped", "J1_J_per_m2", 1);
  EXPECT_NEAR(js / jd, 1.0, 0.005) << "static " << js << ", damped " << jd;
  const auto status = nlohmann::json::parse(read_text(dir_ / "static" / "run.json"));
  EXPECT_TRUE(status["static"]["reached"].get<bool>()) << status.dump();
}

// uGIMP at 2 mm: particles at the DCB's loaded corners carried velocities the grid does not see
// (+-2e-3 m/s, alternating cell by cell), which the nodes' damping never reached, and the run was not
// static by 2 s with any stress update but USL. Task 5 now damps that part of the particles' velocity
// too (docs/speed-accuracy.md, dcb_j.json).
TEST_F(StaticRun, AUgimpDcbAtTwoMillimetreCellsRelaxesToStaticAndGivesTheJOfItsLongDampedRun) {
  const std::string sets = "--set mpm.shape_function=ugimp --set 'crack_tips={\"contour\": \"circle\", \"radius\": 2}'";
  auto r = run("dcb_crack.json", "damped", sets);
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("dcb_crack.json", "static", sets + " --set damping=null --set 'static={}' --set time.end=2");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto status = nlohmann::json::parse(read_text(dir_ / "static" / "run.json"));
  EXPECT_TRUE(status["static"]["reached"].get<bool>()) << status.dump();
  const double js = last_tip_value(dir_ / "static", "J1_J_per_m2", 1), jd = last_tip_value(dir_ / "damped", "J1_J_per_m2", 1);
  EXPECT_NEAR(js / jd, 1.0, 0.005) << "static " << js << ", damped " << jd;
}

TEST_F(StaticRun, AnUncrackedUgimpBeamLoadedAtItsCornersBecomesStaticAsALinearOneDoes) {
  const std::string sets = "--set cracks=null --set crack_tips=null --set damping=null --set 'static={}' --set time.end=2";
  for (const std::string sf : {"linear", "ugimp"}) {
    const auto r = run("dcb_crack.json", sf, sets + " --set mpm.shape_function=" + sf);
    ASSERT_EQ(r.code, 0) << sf << ": " << r.err;
    const auto status = nlohmann::json::parse(read_text(dir_ / sf / "run.json"));
    EXPECT_TRUE(status["static"]["reached"].get<bool>()) << sf << ": " << status.dump();
    // Linear reaches it at 0.075 s, about 3 / damping (69 /s): the uGIMP beam within the same few periods.
    EXPECT_LT(status["time"].get<double>(), 0.2) << sf;
  }
}

TEST_F(StaticRun, ARunNotStaticByItsEndTimeStopsWithExit3AndSaysSo) {
  auto r = run("cracked_strip.json", "short", "--set time.end=0.2");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("not static by time.end"), std::string::npos) << r.err;
  const auto status = nlohmann::json::parse(read_text(dir_ / "short" / "run.json"));
  EXPECT_EQ(status["status"], "aborted");
  EXPECT_NE(status["message"].get<std::string>().find("raise time.end"), std::string::npos);
}

TEST_F(StaticRun, BadStaticSettingsAreRefusedNamingTheKey) {
  auto r = run_cleave("check '" CLEAVE_SOURCE_DIR "/data/scenes/cracked_strip.json' --set damping.kinetic=10", dir_ / "o.txt",
                      dir_ / "e.txt");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("damping.kinetic"), std::string::npos) << r.err;
  r = run_cleave("check '" CLEAVE_SOURCE_DIR "/data/scenes/cracked_strip.json' --set static.tolerance=0.5", dir_ / "o.txt",
                 dir_ / "e.txt");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("static.tolerance"), std::string::npos) << r.err;
  r = run_cleave("check '" CLEAVE_SOURCE_DIR "/data/scenes/cracked_strip.json' --set static.tol=1e-3", dir_ / "o.txt",
                 dir_ / "e.txt");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("static"), std::string::npos) << r.err;
}
