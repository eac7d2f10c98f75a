// cleave fit on a run: the fit of the cracked strip's own fringes against the K the run computed
// from J (issue 21: within 2 % at points 1-9 mm from the tip), calibration of a wrong fringe
// constant, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <regex>
#include <sstream>

#include "cli_support.hpp"
#include "viz/fit/williams.hpp"

using namespace cleave::test;

namespace {
class FitCli : public CliTest {
 protected:
  FitCli() : CliTest("test_viz_fit_cli") {}
};

double number_after(const std::string& text, const std::string& label) {
  const auto at = text.find(label);
  if (at == std::string::npos) return NAN;
  return std::strtod(text.c_str() + at + label.size(), nullptr);
}

// The strip of data/scenes/cracked_strip.json at 0.5 mm cells, relaxed to static (about 20 s on two
// cores), made once per test process.
const fs::path& strip_run() {
  static const fs::path dir = [] {
    const fs::path d = fresh_dir(fs::path(CLEAVE_BINARY_DIR) / ("test_viz_fit_cli_strip_" + std::to_string(getpid())));
    const auto r = run_cleave("run '" CLEAVE_SOURCE_DIR "/data/scenes/cracked_strip.json' --quiet --set resolution=0.5 "
                              "--out '" + (d / "run").string() + "'",
                              d / "o.txt", d / "e.txt");
    EXPECT_EQ(r.code, 0) << r.err;
    return d / "run";
  }();
  return dir;
}
}  // namespace

TEST_F(FitCli, TheCrackedStripsOwnFringesGiveTheKFromJWithin2PercentAndCalibrateAWrongFringeConstantBack) {
  // One run for both checks (CTest runs each case in a process of its own).
  const fs::path run = strip_run();
  for (int tip : {0, 1}) {
    const auto r = run_headless("fit '" + run.string() + "' --frame last --sample 1,9 --fringe-constant 7 "
                                "--thickness 5.7 --tip-index " + std::to_string(tip), dir_);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("1..9 mm"), std::string::npos) << "lengths in the scene's unit (mm)\n" << r.out;
    const double ratio = number_after(r.out, "fit / run K_I = ");
    EXPECT_NEAR(ratio, 1.0, 0.02) << r.out;
  }
  // Points "measured" on the run's fringes with f = 7 N/mm/fringe, calibrated from a wrong 9.
  const auto s = run_headless("fit '" + run.string() + "' --frame last --sample 2,9 --fringe-constant 7 "
                              "--thickness 5.7 --out '" + (dir_ / "sampled").string() + "'", dir_);
  ASSERT_EQ(s.code, 0) << s.err;
  std::ifstream in(dir_ / "sampled_points.csv");
  std::ofstream pts(dir_ / "points.txt");
  std::string line;
  std::getline(in, line);
  int n = 0;
  while (std::getline(in, line)) {
    double v[7];
    char c;
    std::istringstream ss(line);
    ss >> v[0] >> c >> v[1] >> c >> v[2] >> c >> v[3] >> c >> v[4] >> c >> v[5] >> c >> v[6];
    pts << v[0] * 1e3 << ' ' << v[1] * 1e3 << ' ' << v[4] << '\n', ++n;  // x, y in mm, measured N
  }
  pts.close();
  ASSERT_GT(n, 100);
  const auto r = run_headless("fit '" + run.string() + "' --frame last --points '" + (dir_ / "points.txt").string() +
                              "' --calibrate fringe-constant --fringe-constant 9 --thickness 5.7", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NEAR(number_after(r.out, "fringe constant that fits: "), 7.0, 0.07) << r.out;
}

TEST_F(FitCli, BadInputExitsWith2AndTheReason) {
  std::ofstream(dir_ / "three.txt") << "1 2 3\n2 3 2\n3 1 1\n";
  auto r = run_headless("fit --points '" + (dir_ / "three.txt").string() + "' --tip 0,0 --fringe-constant 7 --thickness 5.7", dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("needs more points"), std::string::npos) << r.err;
  r = run_headless("fit --points '" + (dir_ / "none.txt").string() + "' --tip 0,0 --fringe-constant 7 --thickness 5.7", dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("cannot open"), std::string::npos) << r.err;
  r = run_headless("fit --points '" + (dir_ / "three.txt").string() + "' --tip 0,0 --thickness 5.7", dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--fringe-constant"), std::string::npos) << r.err;
  r = run_headless("fit --points '" + (dir_ / "three.txt").string() + "' --fringe-constant 7 --thickness 5.7", dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--tip"), std::string::npos) << r.err;
  r = run_headless("fit --points '" + (dir_ / "three.txt").string() + "' --tip 0,0 --fringe-constant 7 --thickness 5.7 --terms 9", dir_);
  EXPECT_EQ(r.code, 2);
  // Points off the body: the calibration has nothing to scale.
  ASSERT_EQ(run_cleave("run '" + write_scene("tiny.json", tiny_scene()).string() + "' --quiet --out '" +
                       (dir_ / "tiny").string() + "'", dir_ / "o.txt", dir_ / "e.txt").code, 0);
  std::ofstream(dir_ / "off.txt") << "1 1 2\n1.1 1 3\n1.2 1 1\n";
  r = run_headless("fit '" + (dir_ / "tiny").string() + "' --points '" + (dir_ / "off.txt").string() +
                   "' --calibrate load-scale --fringe-constant 7 --thickness 5.7", dir_);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("on the bodies"), std::string::npos) << r.err;
}

TEST_F(FitCli, PointsInPhotoPixelsThroughAMapOrTwoReferencePixelsGiveTheFitOfTheirModelPositions) {
  // Exact fringes of a known tip field at points 1-9 mm round a tip at (8.9, 0) mm; the same points
  // in pixels of a photo whose top-left corner is at (-26, 40) mm with 0.05 mm per pixel, y down.
  const cleave::viz::TipField f = cleave::viz::tip_field_from_K(8.9e-3, 0, 0, 0.6e6, 0.05e6, -3.3e6);
  std::ofstream mm(dir_ / "mm.txt"), px(dir_ / "px.txt");
  mm.precision(12), px.precision(12);
  for (int i = 0; i < 9; ++i)
    for (int d = -170; d <= 170; d += 10) {
      const double r = 1 + i, th = d * 3.14159265358979 / 180, x = 8.9 + r * std::cos(th), y = r * std::sin(th);
      const double N = f.stress_difference(x * 1e-3, y * 1e-3) * 5.7e-3 / 7e3;
      mm << x << ' ' << y << ' ' << N << '\n';
      px << (x + 26) / 0.05 << ' ' << (40 - y) / 0.05 << ' ' << N << '\n';
    }
  mm.close(), px.close();
  const std::string common = " --tip 8.9,0 --fringe-constant 7 --thickness 5.7 --terms 2";
  const auto a = run_headless("fit --points '" + (dir_ / "mm.txt").string() + "'" + common, dir_);
  const auto b = run_headless("fit --points '" + (dir_ / "px.txt").string() + "' --pixel-map -26,40,0.05" + common, dir_);
  const auto c = run_headless("fit --points '" + (dir_ / "px.txt").string() + "' --pixel-ref 0,0,-26,40,1040,800,26,0" + common, dir_);
  for (const auto* r : {&a, &b, &c}) {
    ASSERT_EQ(r->code, 0) << r->err;
    EXPECT_NEAR(number_after(r->out, "K_I   = "), 0.6, 1e-5) << r->out;
    EXPECT_NEAR(number_after(r->out, "K_II  = "), 0.05, 1e-5) << r->out;
  }
}
