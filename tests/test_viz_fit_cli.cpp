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
#include "viz/job/photo_field.hpp"
#include "viz/raster/series.hpp"
#include "viz/render/headless.hpp"

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
  // A photo that cannot be read.
  for (const std::string cmd : {"fit '" + (dir_ / "tiny").string() + "' --photo '" + (dir_ / "none.png").string() +
                                    "' --map 0,0.05,0.001 --calibrate load-scale --fringe-constant 7 --thickness 5.7",
                                "compare '" + (dir_ / "tiny").string() + "' --photo '" + (dir_ / "none.png").string() +
                                    "' --frame last --map 0,0.05,0.001 --fringes dark --fringe-constant 7"}) {
    r = run_headless(cmd, dir_);
    EXPECT_EQ(r.code, 2) << cmd;
    EXPECT_NE(r.err.find("none.png"), std::string::npos) << r.err;
  }
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

TEST_F(FitCli, APhotoOfTheRunsFringesCalibratesAWrongFringeConstantBackAndGivesKFromItsCentreLines) {
  // A dark-field "photograph" of the strip's fringes (1 mm cells, static) made from the run itself
  // with f = 7 N/mm/fringe: 480 x 600 pixels of 0.1 mm round the crack, intensity sin^2(pi N) with
  // a pixel of blur and +-8 grey levels of noise; calibrated from a wrong 9 N/mm/fringe.
  const fs::path run = dir_ / "strip";
  ASSERT_EQ(run_cleave("run '" CLEAVE_SOURCE_DIR "/data/scenes/cracked_strip.json' --quiet --out '" + run.string() + "'",
                       dir_ / "o.txt", dir_ / "e.txt").code, 0);
  const auto entries = cleave::viz::read_series(run);
  const auto frame = cleave::viz::read_particle_frame(entries.back().file, entries.back().time);
  const cleave::viz::PhotoMap map{-24e-3, 30e-3, 1e-4, 0};
  const auto field = cleave::viz::photo_field(frame, 480, 600, map);
  cleave::viz::PhotoelasticSettings ps;
  ps.fringe_constant = 7e3, ps.thickness = 5.7e-3;
  std::vector<double> I(field.diff.size(), 0.0);
  for (std::size_t t = 0; t < I.size(); ++t)
    if (std::isfinite(field.diff[t])) I[t] = cleave::viz::intensity(field.diff[t], 0, 0, ps);
  cleave::viz::Image photo{480, 600, std::vector<uint8_t>(3 * I.size())};
  unsigned seed = 12345;
  for (int j = 0; j < 600; ++j)
    for (int i = 0; i < 480; ++i) {
      double sum = 0;
      int n = 0;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di)
          if (i + di >= 0 && i + di < 480 && j + dj >= 0 && j + dj < 600) sum += I[std::size_t(j + dj) * 480 + i + di], ++n;
      seed = seed * 1103515245u + 12345u;
      const double noise = double(int(seed >> 16) % 17 - 8);
      const auto g = uint8_t(std::clamp(255.0 * sum / n + noise, 0.0, 255.0));
      std::fill_n(&photo.rgb[3 * (std::size_t(j) * 480 + i)], 3, g);
    }
  cleave::viz::write_png(dir_ / "photo.png", photo);
  const auto r = run_headless("fit '" + run.string() + "' --photo '" + (dir_ / "photo.png").string() +
                              "' --map -24,30,0.1 --calibrate fringe-constant --fringe-constant 9 --thickness 5.7", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NEAR(number_after(r.out, "fringe constant that fits: "), 7.0, 0.07) << r.out;
  // K from the photo alone: its dark and bright centre-lines 1-9 mm from the right-hand tip, orders
  // counted on the run's fringes, fitted; against the run's K from J, the 2 % for a frame.
  const auto k = run_headless("fit '" + run.string() + "' --photo '" + (dir_ / "photo.png").string() +
                              "' --map -24,30,0.1 --radii 1,9 --tip-index 1 --fringe-constant 7 --thickness 5.7", dir_);
  ASSERT_EQ(k.code, 0) << k.err;
  EXPECT_GT(number_after(k.out, "read "), 1000) << k.out;
  EXPECT_NEAR(number_after(k.out, "photo fit / run K_I = "), 1.0, 0.02) << k.out;
  std::printf("%s", k.out.c_str());
  // compare: the centre-line overlay and the folded fringe orders agree with the photo.
  const auto c = run_headless("compare '" + run.string() + "' --photo '" + (dir_ / "photo.png").string() +
                              "' --frame last --map -24,30,0.1 --length-unit mm --fringes dark --fringe-constant 7 "
                              "--thickness 5.7 --smooth 0 --out '" + (dir_ / "cmp").string() + "'", dir_);
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_GT(number_after(c.out, "correlation "), 0.9) << c.out;
  EXPECT_TRUE(fs::exists(dir_ / "cmp_overlay.png"));
  std::printf("%s%s", r.out.c_str(), c.out.c_str());
  if (const char* keep = std::getenv("CLEAVE_KEEP_IMAGES"))  // to look at: the photo and the overlay
    for (const char* f : {"photo.png", "cmp_overlay.png", "cmp_side_by_side.png"}) fs::copy_file(dir_ / f, fs::path(keep) / f, fs::copy_options::overwrite_existing);
}

TEST(LoadScale, ADrawnFrameCarriesItsLoadScaleIntoEveryLinearField) {
  cleave::viz::ParticleFrame f;
  f.x = {{0, 0, 0}, {1e-3, 0, 0}};
  f.arrays["stress"] = {6, {1, 2, 3, 4, 0, 0, 5, 6, 7, 8, 0, 0}};
  f.arrays["principal_stress_difference"] = {1, {3, 4}};
  f.arrays["material"] = {1, {0, 1}};
  cleave::viz::RenderOptions o;
  o.smooth = 0, o.load_scale = 2.5;
  const auto d = cleave::viz::drawn_frame(f, o);
  EXPECT_DOUBLE_EQ(d.arrays.at("stress").values[6], 12.5);
  EXPECT_DOUBLE_EQ(d.arrays.at("principal_stress_difference").values[1], 10.0);
  EXPECT_DOUBLE_EQ(d.arrays.at("material").values[1], 1.0);  // not a load-linear field
}

TEST_F(FitCli, AFringeConstantInKgfPerMmGivesTheSameFitAsInNewtons) {
  const cleave::viz::TipField f = cleave::viz::tip_field_from_K(0, 0, 0, 0.6e6, 0.0, -3.3e6);
  std::ofstream mm(dir_ / "mm.txt");
  mm.precision(12);
  for (int i = 1; i <= 8; ++i)
    for (int d = -170; d <= 170; d += 20) {
      const double th = d * 3.14159265358979 / 180, x = i * std::cos(th), y = i * std::sin(th);
      mm << x << ' ' << y << ' ' << f.stress_difference(x * 1e-3, y * 1e-3) * 5.7e-3 / 7e3 << '\n';
    }
  mm.close();
  const std::string pts = "fit --points '" + (dir_ / "mm.txt").string() + "' --tip 0,0 --thickness 5.7 --terms 2 ";
  const auto a = run_headless(pts + "--fringe-constant 7", dir_);
  const auto b = run_headless(pts + "--fringe-constant " + std::to_string(7 / 9.80665) + ",kgf", dir_);
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_NEAR(number_after(a.out, "K_I   = "), 0.6, 1e-5);
  EXPECT_NEAR(number_after(b.out, "K_I   = "), 0.6, 1e-5);
}
