// Figures a paper can use as they are (issue 15, "Figures"), through the command line: frames named
// by their index in the series, sections of 3D runs along any axis, and fringe images of the
// default scene that are white, cropped to the bodies, with a scale bar, and whose stress smoothing
// brings two resolutions closer. The parts (text, ticks, outlines, smoothing): test_viz_figure_parts.cpp.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "viz/job/render_job.hpp"
#include "viz/raster/rasterize.hpp"

namespace cleave::viz {
namespace {

namespace fs = std::filesystem;
using test::read_text;
constexpr auto& run = test::run_headless;  // `cleave ARGS` with DISPLAY unset (cli_support.hpp)

// A fresh directory per test (CTest runs each test in its own process, concurrently).
fs::path fresh_dir(const std::string& name) {
  return test::fresh_dir(fs::path(CLEAVE_BINARY_DIR) / ("test_viz_figures_" + name + "_" + std::to_string(getpid())));
}

bool is_white(const Image& im, int x, int y) {
  const uint8_t* c = &im.rgb[3 * (std::size_t(y) * im.width + x)];
  return c[0] > 250 && c[1] > 250 && c[2] > 250;
}

// Bounding box {x0, y0, x1, y1} (pixels, inclusive) of the pixels that are not white within rows
// [row0, row1).
std::array<int, 4> ink_box(const Image& im, int row0, int row1) {
  std::array<int, 4> b{im.width, im.height, -1, -1};
  for (int y = row0; y < row1; ++y)
    for (int x = 0; x < im.width; ++x)
      if (!is_white(im, x, y)) b = {std::min(b[0], x), std::min(b[1], y), std::max(b[2], x), std::max(b[3], y)};
  return b;
}

// --- frames named by their index --------------------------------------------------------------------

TEST(RenderFiles, FramesAreNamedByTheirIndexInTheSeriesSoLastDoesNotOverwriteFirst) {
  const fs::path dir = fresh_dir("names");
  auto r = run(std::string("run ") + CLEAVE_SOURCE_DIR "/data/scenes/brazilian_disk.json --quiet --threads 1 " +
                   "--set resolution=1 --set time.end=0.3 --out " + (dir / "disk").string(),
               dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const fs::path images = dir / "img";
  const std::string common = "render " + (dir / "disk").string() + " --field syy --size 200x200 --images " + images.string();
  r = run(common + " --frames first", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string first = read_text(images / "syy_000000.png");
  ASSERT_FALSE(first.empty());
  r = run(common + " --frames last", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(images / "syy_000006.png")) << "the last of 7 frames is frame 6";
  EXPECT_EQ(read_text(images / "syy_000000.png"), first) << "the first frame's image was overwritten";
  // every:3 names frames 0, 3, 6 and still encodes a movie of those three.
  r = run(common + " --frames every:3 --fringes dark --fringe-constant 7 --thickness 5 --movie m.mp4", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"fringes_000000.png", "fringes_000003.png", "fringes_000006.png"})
    EXPECT_TRUE(fs::exists(images / f)) << f;
  EXPECT_FALSE(fs::exists(images / "fringes_000001.png"));
  ASSERT_TRUE(fs::exists(images / "m.mp4"));
  EXPECT_GT(fs::file_size(images / "m.mp4"), 500u);
  for (const auto& e : fs::directory_iterator(images)) EXPECT_NE(e.path().filename().string()[0], '.') << "temporary left";
  fs::remove_all(dir);
}

// --- sections ---------------------------------------------------------------------------------------

// A box lattice whose middle planes lie on faces between particle layers (where one cuts), its
// positions rounded as a solver leaves them: each section is one whole layer with the body's extent.
TEST(RasterCutPlane, ASectionThroughTheMiddleAlongXYOrZHasTheExtentOfTheBody) {
  const double s = 0.0025, L[3] = {0.04, 0.03, 0.02};
  const int n[3] = {16, 12, 8};
  ParticleFrame f;
  f.dim = 3;
  unsigned seed = 12345;
  auto jitter = [&] {  // +-1e-16 m: the rounding of a position that went through a time step
    seed = seed * 1103515245u + 12345u;
    return (double((seed >> 8) & 0xffff) / 65535.0 - 0.5) * 2e-16;
  };
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        f.x.push_back({(i + 0.5) * s + jitter(), (j + 0.5) * s + jitter(), (k + 0.5) * s + jitter()});
        f.arrays["size"].values.push_back(s);
      }
  for (int axis = 0; axis < 3; ++axis) {
    std::array<double, 3> normal{0, 0, 0};
    normal[axis] = 1;
    const ParticleFrame c = cut_plane(f, {L[0] / 2, L[1] / 2, L[2] / 2}, normal);
    const int a = axis == 0 ? 1 : 0, b = axis == 2 ? 1 : 2;  // the section's (u, v) axes
    EXPECT_EQ(c.x.size(), std::size_t(n[a] * n[b])) << "normal along axis " << axis << ": not one whole layer";
    const View v = fit_view(c, 400, 400, std::nullopt, 1.0, 0.0);
    EXPECT_NEAR(v.x1 - v.x0 >= v.y1 - v.y0 ? v.x1 - v.x0 : v.y1 - v.y0, std::max(L[a], L[b]), 1e-9);
    const auto box = bodies_box(c, std::nullopt, 0.0);
    EXPECT_NEAR(box[2] - box[0], L[a], 1e-9) << "axis " << axis;
    EXPECT_NEAR(box[3] - box[1], L[b], 1e-9) << "axis " << axis;
  }
}

// The same through the command line, on a run: the section drawn along x, y and z in every frame
// is whole and has the aspect ratio of the body's section (a 40 x 20 x 20 mm bar held at x = 0,
// cells of 5 mm: the middle planes are faces between particle layers).
TEST(RasterCutPlane, RenderedSectionsOfARunAlongXYAndZShowTheWholeSection) {
  const fs::path dir = fresh_dir("cut");
  std::ofstream(dir / "bar.json") << R"({"analysis": {"type": "3d"}, "grid": {"cell_size": 0.005},
    "materials": [{"name": "m", "type": "linear_elastic", "E": 1e9, "nu": 0.3, "density": 1000}],
    "bodies": [{"name": "b", "material": "m", "velocity": [0, -5, 0],
                "shape": {"type": "box", "min": [0, 0, 0], "max": [0.04, 0.02, 0.02]}}],
    "loads": [{"type": "velocity", "region": {"min": [0, -1, -1], "max": [0, 1, 1]}, "velocity": [0, 0, 0]}],
    "time": {"end": 2e-5}, "output": {"interval": 1e-5}})";
  auto r = run("run " + (dir / "bar.json").string() + " --quiet --threads 1 --out " + (dir / "out").string(), dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const char* normals[3] = {"1,0,0", "0,1,0", "0,0,1"};
  const double expected[3] = {20.0 / 20, 40.0 / 20, 40.0 / 20};
  for (int axis = 0; axis < 3; ++axis) {
    const fs::path images = dir / ("cut" + std::to_string(axis));
    r = run("render " + (dir / "out").string() + " --field von_mises --cut-plane 20,10,10," + normals[axis] +
                " --length-unit mm --size 600x600 --no-time --no-colorbar --no-scale-bar --images " + images.string(),
            dir);
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* frame : {"von_mises_000000.png", "von_mises_000001.png", "von_mises_000002.png"}) {
    SCOPED_TRACE(frame);
    const Image im = read_image(images / frame);
    const auto b = ink_box(im, 0, im.height);
    ASSERT_GE(b[2], b[0]) << "nothing drawn";
    const double aspect = double(b[2] - b[0] + 1) / (b[3] - b[1] + 1);
    EXPECT_NEAR(aspect, expected[axis], 0.05 * expected[axis]) << "normal " << normals[axis];
    EXPECT_GT(b[2] - b[0] + 1, 500) << "normal " << normals[axis] << ": the section is not fitted to the image";
    std::size_t holes = 0;
    for (int y = b[1]; y <= b[3]; ++y)
      for (int x = b[0]; x <= b[2]; ++x) holes += is_white(im, x, y);
    EXPECT_LT(holes, std::size_t(b[2] - b[0] + 1) * (b[3] - b[1] + 1) / 100) << "normal " << normals[axis] << ": holes";
    }
  }
  fs::remove_all(dir);
}

// --- the default scene's figure -----------------------------------------------------------------------

// The five disks at a coarse resolution: a 1280 x 400 fringe image is white around the bodies,
// cropped to them (they span its width), carries a scale bar below them and is free of dark
// blue-grey; and the smoothing brings the fringes of this run and of one at twice its resolution
// closer together.
class RenderFiveDiskFigures : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fresh_dir("five");
    for (const auto& [name, res] : {std::pair{"coarse", "2"}, {"fine", "1"}}) {
      const auto r = run(std::string("run ") + CLEAVE_SOURCE_DIR "/data/scenes/five_disks.json --quiet --threads 1 " +
                             "--set time.end=0.024 --set resolution=" + res + " --out " + (dir_ / name).string(),
                         dir_);
      ASSERT_EQ(r.code, 0) << r.err;
    }
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static fs::path dir_;
};
fs::path RenderFiveDiskFigures::dir_;

TEST_F(RenderFiveDiskFigures, AFringeFigureIsWhiteCroppedToTheBodiesWithAScaleBar) {
  const auto r = run("render " + (dir_ / "fine").string() + " --fringes seed002 --frames last --size 1280x400 --images " +
                         (dir_ / "img").string(),
                     dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  fs::path png;
  for (const auto& e : fs::directory_iterator(dir_ / "img")) png = e.path();
  const Image im = read_image(png);
  EXPECT_EQ(im.width, 1280);
  EXPECT_LT(im.height, 400) << "not cropped to the bodies";
  EXPECT_TRUE(is_white(im, 0, 0) && is_white(im, im.width - 1, im.height - 1)) << "background not white";
  // The bodies (rows between the time stamp band and the scale bar band) span the width.
  const auto b = ink_box(im, int(0.12 * im.height), int(0.8 * im.height));
  EXPECT_LT(b[0], int(0.04 * im.width));
  EXPECT_GT(b[2], int(0.96 * im.width));
  // A scale bar: a long dark run in the bottom rows, at the left.
  int longest = 0;
  for (int y = int(0.85 * im.height); y < im.height; ++y) {
    int run_len = 0;
    for (int x = 0; x < im.width / 3; ++x) {
      const uint8_t* c = &im.rgb[3 * (std::size_t(y) * im.width + x)];
      run_len = c[0] < 60 && c[1] < 60 && c[2] < 60 ? run_len + 1 : 0;
      longest = std::max(longest, run_len);
    }
  }
  EXPECT_GT(longest, 60) << "no scale bar";
}

TEST_F(RenderFiveDiskFigures, SmoothingBringsTheFringesOfTwoResolutionsCloserTogether) {
  auto rms = [&](double smooth) {
    const auto r = run("compare " + (dir_ / "coarse").string() + " --run " + (dir_ / "fine").string() +
                           " --frame last --fringes seed002 --smooth " + std::to_string(smooth),
                       dir_);
    EXPECT_EQ(r.code, 0) << r.err;
    std::smatch m;
    EXPECT_TRUE(std::regex_search(r.out, m, std::regex("RMS difference ([0-9.]+)"))) << r.out;
    return m.empty() ? 0.0 : std::stod(m[1]);
  };
  const double before = rms(0), after = rms(1.5);
  std::printf("fringe order RMS difference, resolution 2 against 1: %.4f as written, %.4f smoothed\n", before, after);
  EXPECT_LT(after, 0.9 * before);
}

}  // namespace
}  // namespace cleave::viz
