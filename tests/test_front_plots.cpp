// `cleave plot` for 3D crack fronts (viz/job/front_plots.hpp): K_I, K_II, K_III along each front at
// a chosen output time and K_I against time at chosen front nodes, from a crack_fronts.csv written
// here (a penny crack under tension), with and without the reference columns; and the plot styles
// (dashed lines, gaps, markers) those plots use.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "viz/job/front_plots.hpp"
#include "viz/render/headless.hpp"

namespace cleave::viz {
namespace {

namespace fs = std::filesystem;
constexpr auto& run = test::run_headless;  // `cleave ARGS` with DISPLAY unset (cli_support.hpp)
using RGB = std::array<unsigned char, 3>;

// The penny crack: radius a = 5 mm, remote tension sigma = 10 MPa, so K_I = 2 sigma sqrt(a/pi)
// (0.798 MPa m^1/2) all along the front; 24 front nodes at phi = 15 deg steps, s = a phi.
constexpr double kA = 5e-3, kSigma = 10e6;
const double kKref = 2 * kSigma * std::sqrt(kA / std::numbers::pi);
constexpr int kNodes = 24;
constexpr std::array<double, 3> kTimes{1e-5, 2e-5, 3e-5};

struct Columns {
  bool ref = true;              // phi_rad and KI_ref.., as when the scene names a reference solution
  std::set<int> flagged_last;   // nodes flagged at the last time
};

// K at node n, time index k: the load ramps up (k+1)/3 of the reference; K_I varies 4 % along the
// front, K_II and K_III are small.
std::array<double, 3> k_of(int n, int k) {
  const double phi = 2 * std::numbers::pi * n / kNodes, ramp = (k + 1) / 3.0;
  return {ramp * kKref * (1 + 0.04 * std::cos(2 * phi)), 0.08 * ramp * kKref * std::cos(phi),
          -0.06 * ramp * kKref * std::sin(phi)};
}

void write_run(const fs::path& d, const Columns& c = {}) {
  fs::create_directories(d);
  std::ofstream g(d / "global.csv");
  g << "time_s,kinetic_energy_J,strain_energy_J,total_energy_J,external_work_J\n";
  for (int k = 0; k <= 30; ++k) g << k * 1e-6 << "," << 1e-3 * k << "," << 2e-3 * k << "," << 3e-3 * k << "," << 3e-3 * k << "\n";
  std::ofstream f(d / "crack_fronts.csv");
  f.precision(17);
  f << "time_s,crack,front,node,s_m,x_m,y_m,z_m,J1_J_per_m2,J2_J_per_m2,KI_Pa_sqrt_m,KII_Pa_sqrt_m,"
       "KIII_Pa_sqrt_m,flag";
  if (c.ref) f << ",phi_rad,KI_ref_Pa_sqrt_m,KII_ref_Pa_sqrt_m,KIII_ref_Pa_sqrt_m";
  f << "\n";
  for (int k = 0; k < 3; ++k)
    for (int n = 0; n < kNodes; ++n) {
      const double phi = 2 * std::numbers::pi * n / kNodes;
      const auto K = k_of(n, k);
      const int flag = k == 2 && c.flagged_last.count(n) ? 1 : 0;
      f << kTimes[k] << ",0,0," << n << "," << kA * phi << "," << kA * std::cos(phi) << "," << kA * std::sin(phi)
        << ",0.01,1,0," << K[0] << "," << K[1] << "," << K[2] << "," << flag;
      if (c.ref) f << "," << phi << "," << kKref << ",0,0";
      f << "\n";
    }
}

int colour_distance(const Image& im, std::size_t p, const RGB& c) {
  int d = 0;
  for (int i = 0; i < 3; ++i) d = std::max(d, std::abs(int(im.rgb[3 * p + i]) - int(c[i])));
  return d;
}
// Pixels within `tol` of colour c, in columns [x0, x1) (all by default).
int count_near(const Image& im, const RGB& c, int tol, int x0 = 0, int x1 = -1) {
  if (x1 < 0) x1 = im.width;
  int n = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = x0; x < x1; ++x) n += colour_distance(im, std::size_t(y) * im.width + x, c) <= tol;
  return n;
}
const RGB kBlue{31, 119, 180}, kRed{214, 39, 40}, kGreen{44, 160, 44}, kWhite{255, 255, 255};

const PlotSeries* find(const FrontPlot& p, const std::string& name) {
  for (const auto& s : p.series)
    if (s.name == name) return &s;
  return nullptr;
}

class FrontPlots : public test::CliTest {
 protected:
  FrontPlots() : CliTest("front_plots_") {}
  fs::path images() const { return dir_ / "run" / "render"; }
};

TEST_F(FrontPlots, KAlongTheFrontIsDrawnAtTheChosenTimeWithTheReference) {
  write_run(dir_ / "run");
  const FrontTable t = read_crack_fronts(dir_ / "run" / "crack_fronts.csv");
  ASSERT_EQ(t.rows.size(), 3u * kNodes);
  EXPECT_TRUE(t.has_phi);
  FrontPlotOptions o;
  o.time = 1.4e-5;  // nearest output time: 1e-5
  const FrontPlot p = k_along_front(t, o);
  EXPECT_NE(p.title.find("10.0"), std::string::npos) << p.title;
  EXPECT_EQ(p.xlabel, "arc length along the front s (mm)");
  EXPECT_EQ(p.ylabel, "K (MPa m^1/2)");
  for (const char* name : {"KI", "KII", "KIII", "KI reference", "KII reference", "KIII reference"})
    ASSERT_NE(find(p, name), nullptr) << name;
  const PlotSeries& KI = *find(p, "KI");
  ASSERT_EQ(KI.y.size(), std::size_t(kNodes));
  for (int n = 0; n < kNodes; ++n) {
    EXPECT_NEAR(KI.x[n], kA * 2 * std::numbers::pi * n / kNodes * 1e3, 1e-9);  // s in mm
    EXPECT_NEAR(KI.y[n], k_of(n, 0)[0] * 1e-6, 1e-12);                        // K at t = 10 us, MPa m^1/2
  }
  const PlotSeries& ref = *find(p, "KI reference");
  EXPECT_EQ(ref.line, PlotSeries::Line::Dashed);
  EXPECT_EQ(KI.line, PlotSeries::Line::Solid);
  EXPECT_EQ(ref.colour, KI.colour) << "the reference in its mode's colour";
  EXPECT_NEAR(ref.y[7], kKref * 1e-6, 1e-12);
  EXPECT_EQ(find(p, "flagged (contour incomplete)"), nullptr) << "no node is flagged";
  // Default: the last time.
  EXPECT_NEAR(find(k_along_front(t, {}), "KI")->y[3], k_of(3, 2)[0] * 1e-6, 1e-12);

  // The images: the size asked for, the three modes' colours, and the time chosen shows.
  const fs::path d = dir_ / "run";
  auto r = run("plot " + d.string() + " --size 640x400 --front-time 1.4e-5", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"energy.png", "K_front.png", "K_front_time.png"}) {
    EXPECT_TRUE(fs::exists(images() / f)) << f;
    EXPECT_NE(r.out.find(f), std::string::npos) << "printed: " << f;
  }
  const Image at_10us = read_image(images() / "K_front.png");
  ASSERT_EQ(at_10us.width, 640);
  ASSERT_EQ(at_10us.height, 400);
  const int total = 640 * 400;
  EXPECT_LT(count_near(at_10us, kWhite, 0), total - 4000) << "the plot is (nearly) blank";
  EXPECT_GT(count_near(at_10us, kBlue, 40), 300) << "KI";
  EXPECT_GT(count_near(at_10us, kRed, 40), 200) << "KII";
  EXPECT_GT(count_near(at_10us, kGreen, 40), 200) << "KIII";
  r = run("plot " + d.string() + " --size 640x400", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(read_image(images() / "K_front.png").rgb, at_10us.rgb) << "the last time draws other K";
}

TEST_F(FrontPlots, KAgainstTimeIsDrawnAtTheFirstMiddleAndLastNodeOrTheNodesGiven) {
  write_run(dir_ / "run");
  const FrontTable t = read_crack_fronts(dir_ / "run" / "crack_fronts.csv");
  const FrontPlot p = k_against_time(t, {});
  EXPECT_EQ(p.xlabel, "time (ms)");
  for (int n : {0, 12, 23}) {
    const PlotSeries* s = find(p, "KI node " + std::to_string(n));
    ASSERT_NE(s, nullptr) << n;
    ASSERT_EQ(s->x.size(), 3u);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(s->x[k], kTimes[k] * 1e3, 1e-12);
      EXPECT_NEAR(s->y[k], k_of(n, k)[0] * 1e-6, 1e-12);
    }
  }
  // The reference is the same at every node: drawn once, dashed.
  const PlotSeries* ref = find(p, "KI reference");
  ASSERT_NE(ref, nullptr);
  EXPECT_EQ(ref->line, PlotSeries::Line::Dashed);
  EXPECT_EQ(p.series.size(), 4u);
  FrontPlotOptions o;
  o.nodes = std::vector<int>{3, 7, 3};
  const FrontPlot q = k_against_time(t, o);
  EXPECT_NE(find(q, "KI node 3"), nullptr);
  EXPECT_NE(find(q, "KI node 7"), nullptr);
  EXPECT_EQ(find(q, "KI node 0"), nullptr);
  EXPECT_EQ(q.series.size(), 3u) << "node 3 once, node 7, the reference";

  const fs::path d = dir_ / "run";
  auto r = run("plot " + d.string() + " --size 640x400", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const Image def = read_image(images() / "K_front_time.png");
  ASSERT_EQ(def.width, 640);
  ASSERT_EQ(def.height, 400);
  // Nodes 0 and 12 (phi = 0 and 180 deg) have the same K_I: node 12 (red) is drawn over node 0 (blue).
  EXPECT_GT(count_near(def, kRed, 40), 200) << "node 12";
  EXPECT_GT(count_near(def, kGreen, 40), 200) << "node 23";
  r = run("plot " + d.string() + " --size 640x400 --front-nodes 3,7", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const Image given = read_image(images() / "K_front_time.png");
  EXPECT_NE(given.rgb, def.rgb);
  EXPECT_GT(count_near(given, kBlue, 40), 200) << "node 3";
  EXPECT_GT(count_near(given, kRed, 40), 200) << "node 7";
}

// A node whose contour was incomplete (flag != 0) is not joined to its neighbours: its curve breaks
// there, and its K is drawn as a black cross of the one "flagged" series.
TEST_F(FrontPlots, FlaggedNodesBreakTheCurvesAndAreDrawnAsBlackCrosses) {
  write_run(dir_ / "run", Columns{true, {5, 6, 23}});
  const FrontTable t = read_crack_fronts(dir_ / "run" / "crack_fronts.csv");
  const FrontPlot p = k_along_front(t, {});
  const PlotSeries& KI = *find(p, "KI");
  EXPECT_TRUE(std::isnan(KI.y[5]) && std::isnan(KI.y[6]) && std::isnan(KI.y[23]));
  EXPECT_NEAR(KI.y[4], k_of(4, 2)[0] * 1e-6, 1e-12);
  const PlotSeries* flagged = find(p, "flagged (contour incomplete)");
  ASSERT_NE(flagged, nullptr);
  EXPECT_EQ(flagged->line, PlotSeries::Line::None);
  EXPECT_TRUE(flagged->markers);
  EXPECT_EQ(flagged->colour, (RGB{0, 0, 0}));
  EXPECT_EQ(flagged->x.size(), 9u) << "3 nodes x 3 modes";
  EXPECT_NEAR(flagged->y[0], k_of(5, 2)[0] * 1e-6, 1e-12) << "the flagged K as written";
  // In time: node 23 breaks at the last time and is a cross there; node 0 is whole.
  const FrontPlot q = k_against_time(t, {});
  EXPECT_TRUE(std::isnan(find(q, "KI node 23")->y[2]));
  EXPECT_FALSE(std::isnan(find(q, "KI node 0")->y[2]));
  ASSERT_NE(find(q, "flagged (contour incomplete)"), nullptr);
  EXPECT_EQ(find(q, "flagged (contour incomplete)")->x.size(), 1u);

  auto r = run("plot " + (dir_ / "run").string() + " --size 640x400", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const Image with_flags = read_image(images() / "K_front.png");
  write_run(dir_ / "run");
  r = run("plot " + (dir_ / "run").string() + " --size 640x400", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(read_image(images() / "K_front.png").rgb, with_flags.rgb);
}

TEST_F(FrontPlots, TheEllipseAngleAxisIsInDegreesAndNeedsThePhiColumn) {
  write_run(dir_ / "run");
  FrontPlotOptions o;
  o.axis = FrontAxis::EllipseAngle;
  const FrontPlot p = k_along_front(read_crack_fronts(dir_ / "run" / "crack_fronts.csv"), o);
  EXPECT_EQ(p.xlabel, "ellipse angle phi (deg)");
  EXPECT_NEAR(find(p, "KI")->x[6], 90.0, 1e-9);
  auto r = run("plot " + (dir_ / "run").string() + " --size 640x400 --front-axis phi", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(images() / "K_front.png"));

  // Without a reference solution there is no phi_rad column: an error naming the option, and no image.
  const fs::path d = dir_ / "no_ref";
  write_run(d, Columns{false, {}});
  EXPECT_THROW(k_along_front(read_crack_fronts(d / "crack_fronts.csv"), o), std::invalid_argument);
  r = run("plot " + d.string() + " --size 640x400 --front-axis phi", dir_);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--front-axis"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("elliptical"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(d / "render" / "K_front.png"));
  EXPECT_FALSE(fs::exists(d / "render" / "energy.png")) << "a bad option writes no image";
}

TEST_F(FrontPlots, ACsvWithoutReferenceColumnsPlotsWithoutAReference) {
  const fs::path d = dir_ / "no_ref";
  write_run(d, Columns{false, {}});
  const FrontTable t = read_crack_fronts(d / "crack_fronts.csv");
  EXPECT_FALSE(t.has_phi);
  EXPECT_FALSE(t.has_ref[0] || t.has_ref[1] || t.has_ref[2]);
  for (const FrontPlot& p : {k_along_front(t, {}), k_against_time(t, {})}) {
    EXPECT_FALSE(p.series.empty());
    for (const auto& s : p.series) {
      EXPECT_EQ(s.name.find("reference"), std::string::npos) << s.name;
      EXPECT_EQ(s.line, PlotSeries::Line::Solid) << s.name;
    }
  }
  const auto r = run("plot " + d.string() + " --size 640x400", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  // K_I along the front in blue; in time, node 12 in red over node 0 (the same K_I).
  for (const auto& [f, colour] : {std::pair{"K_front.png", kBlue}, std::pair{"K_front_time.png", kRed}}) {
    const Image im = read_image(d / "render" / f);
    EXPECT_EQ(im.width, 640) << f;
    EXPECT_GT(count_near(im, colour, 40), 200) << f;
  }
}

// Columns are read by their names, in any order, with their units or bare; flag, KII, KIII, phi and
// the reference may be missing; a last line the solver is still writing is left out; a file
// without a column the plots need is an error naming it.
TEST_F(FrontPlots, ColumnsAreFoundByNameInAnyOrderAndAPartlyWrittenLastRowIsLeftOut) {
  const fs::path d = dir_ / "run";
  fs::create_directories(d);
  {
    std::ofstream f(d / "crack_fronts.csv");
    f << "node,KI,time_s,crack,s_m,front,KI_ref_Pa_sqrt_m\r\n";
    for (int n = 0; n < 4; ++n) f << n << "," << 1e6 * (n + 1) << ",0.001,0," << 1e-3 * n << ",0,\r\n";
    f << "0,2e6,0.002,0";  // cut off
  }
  const FrontTable t = read_crack_fronts(d / "crack_fronts.csv");
  ASSERT_EQ(t.rows.size(), 4u);
  EXPECT_TRUE(t.has_K[0]);
  EXPECT_FALSE(t.has_K[1] || t.has_K[2] || t.has_phi);
  EXPECT_TRUE(t.has_ref[0]);
  EXPECT_EQ(t.rows[2].node, 2);
  EXPECT_DOUBLE_EQ(t.rows[2].K[0], 3e6);
  EXPECT_DOUBLE_EQ(t.rows[2].s, 2e-3);
  EXPECT_TRUE(std::isnan(t.rows[2].K_ref[0])) << "an empty cell has no value";
  EXPECT_EQ(t.rows[2].flag, 0);
  const FrontPlot p = k_along_front(t, {});
  ASSERT_NE(find(p, "KI"), nullptr);
  EXPECT_EQ(find(p, "KII"), nullptr);
  EXPECT_NEAR(find(p, "KI")->y[3], 4.0, 1e-12);
  const auto r = run("plot " + d.string() + " --size 320x240", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(images() / "K_front.png"));

  std::ofstream(d / "crack_fronts.csv") << "time_s,crack,front,node,s_m,KII_Pa_sqrt_m\n0,0,0,0,0,1\n";
  try {
    read_crack_fronts(d / "crack_fronts.csv");
    ADD_FAILURE() << "no KI column, no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("KI_Pa_sqrt_m"), std::string::npos) << e.what();
  }
}

TEST_F(FrontPlots, BadFrontOptionsExitWith2NamingTheOption) {
  const fs::path d = dir_ / "run";
  write_run(d);
  struct Case {
    std::string args, says;
  };
  for (const Case& c : std::vector<Case>{{"--front-time soon", "--front-time"},
                                         {"--front-time -1", "--front-time"},
                                         {"--front-time", "--front-time"},
                                         {"--front-axis theta", "--front-axis"},
                                         {"--front-nodes 1,x", "--front-nodes"},
                                         {"--front-nodes -2", "--front-nodes"},
                                         {"--front-nodes 0,24", "0 to 23"},
                                         {"--front-nodes 24", "--front-nodes"},
                                         {"--cod 0 --front-nodes 1", "--front-nodes"}}) {
    const auto r = run("plot " + d.string() + " " + c.args, dir_);
    EXPECT_EQ(r.code, 2) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << ": " << r.err;
  }
  auto r = run("render " + d.string() + " --front-time 1e-5", dir_);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--front-time is an option of cleave plot"), std::string::npos) << r.err;
  // A run without crack fronts: the options have nothing to act on.
  const fs::path e = dir_ / "energies_only";
  write_run(e);
  fs::remove(e / "crack_fronts.csv");
  r = run("plot " + e.string() + " --front-nodes 1", dir_);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("crack_fronts.csv"), std::string::npos) << r.err;
  r = run("plot " + e.string(), dir_);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(fs::exists(e / "render" / "K_front.png"));
}

// The styles render_plot draws for the front plots; the defaults draw as plots always did.
TEST(PlotStyles, ADashedLineHasGapsANaNBreaksALineAndMarkersAreCrosses) {
  HeadlessContext ctx(640, 400);
  PlotSeries solid{"solid", {0, 10}, {1, 1}};
  PlotSeries low{"low", {0, 10}, {0, 0}};
  const Image a = render_plot(ctx, {solid, low}, "", "", "");
  PlotSeries dashed = solid;
  dashed.line = PlotSeries::Line::Dashed;
  const Image b = render_plot(ctx, {dashed, low}, "", "", "");
  const int n_solid = count_near(a, kBlue, 40), n_dashed = count_near(b, kBlue, 40);
  EXPECT_GT(n_solid, 500);
  EXPECT_LT(n_dashed, 0.85 * n_solid) << "a dashed line leaves gaps";
  EXPECT_GT(n_dashed, 0.2 * n_solid);

  // y = 1 with a NaN at x = 5: no blue in the middle of the plot's width.
  PlotSeries broken{"broken", {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, {1, 1, 1, 1, 1, NAN, 1, 1, 1, 1, 1}};
  const Image c = render_plot(ctx, {broken, low}, "", "", "");
  int first = 640, last = 0;
  for (int x = 0; x < 640; ++x)
    if (count_near(c, kBlue, 40, x, x + 1) > 0 && x < 450) first = std::min(first, x), last = std::max(last, x);
  ASSERT_LT(first, last);
  int gap = 0;  // blue-free columns between the first and last blue column (left of the legend)
  for (int x = first; x <= last; ++x) gap += count_near(c, kBlue, 40, x, x + 1) == 0;
  EXPECT_GT(gap, 20) << "the line breaks at the NaN";

  // Markers only, in a colour of one's own.
  PlotSeries crosses{"crosses", {1, 5, 9}, {0.5, 0.5, 0.5}};
  crosses.line = PlotSeries::Line::None;
  crosses.markers = true;
  crosses.colour = RGB{214, 39, 40};
  const Image m = render_plot(ctx, {low, crosses}, "", "", "", {PlotLegend::Right, 0.05});
  EXPECT_GT(count_near(m, kRed, 40), 20);
  EXPECT_LT(count_near(m, kRed, 40), 1500) << "crosses, not a line";
}

}  // namespace
}  // namespace cleave::viz
