// The headless renderer backend: OSMesa + VTK with no X server and no DISPLAY. Renders a 2D frame
// with a known field image, 3D cubes, a plot, round-trips PNG/JPEG files, makes several contexts,
// and checks the process never tries to reach an X server.
#include "viz/render/headless.hpp"

#include <gtest/gtest.h>
#include <vtkImageData.h>
#include <vtkJPEGWriter.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkRenderWindow.h>
#include <vtkStringOutputWindow.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>

#ifdef __SANITIZE_ADDRESS__
// Tests here measure resident memory across frames and contexts. AddressSanitizer keeps freed blocks
// in a quarantine (256 MB by default), so the resident size grew 478 -> 636 MiB over 60 frames under
// it and 304 -> 305 MiB without it: this binary runs with the quarantine off (use after free is still
// caught in every other test binary of a sanitizer build, and leaks are still detected here).
extern "C" const char* __asan_default_options() { return "quarantine_size_mb=0"; }
#endif
#include <dlfcn.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using namespace cleave::viz;

// --- no X ------------------------------------------------------------------------------------------

// This executable is built with ENABLE_EXPORTS, so these definitions take the place of libX11's and
// libxcb's for every library in the process: any attempt to reach an X server is counted (and fails).
static int g_x_connect_attempts = 0;
extern "C" {
struct _XDisplay;
struct xcb_connection_t;
__attribute__((visibility("default"))) _XDisplay* XOpenDisplay(const char*) {
  ++g_x_connect_attempts;
  return nullptr;
}
__attribute__((visibility("default"))) xcb_connection_t* xcb_connect(const char*, int*) {
  ++g_x_connect_attempts;
  return nullptr;
}
}

// No DISPLAY from the very start (before any test, before VTK is touched).
static const bool g_display_unset = [] {
  unsetenv("DISPLAY");
  return true;
}();

namespace {

// Everything VTK reports (errors, warnings) lands here, so the tests can see that rendering is quiet
// (no "GLEW could not be initialized", no OpenGL errors).
vtkStringOutputWindow* vtk_messages() {
  static vtkStringOutputWindow* window = [] {
    auto* w = vtkStringOutputWindow::New();
    vtkOutputWindow::SetInstance(w);
    return w;
  }();
  return window;
}

int count_open_sockets() {
  int n = 0;
  for (const auto& e : fs::directory_iterator("/proc/self/fd")) {
    std::error_code ec;
    const auto target = fs::read_symlink(e.path(), ec);
    if (!ec && target.string().rfind("socket:", 0) == 0) ++n;
  }
  return n;
}

class VizHeadless : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(g_display_unset);
    unsetenv("DISPLAY");
    ASSERT_EQ(std::getenv("DISPLAY"), nullptr);
    messages_from_ = vtk_messages()->GetOutput().size();
  }
  void TearDown() override {
    EXPECT_EQ(g_x_connect_attempts, 0) << "something tried to open an X display";
    EXPECT_EQ(vtk_messages()->GetOutput().substr(messages_from_), std::string()) << "VTK reported problems";
  }
  // Forget what VTK said so far in this test (a complaint the test provoked).
  void forget_vtk_messages() { messages_from_ = vtk_messages()->GetOutput().size(); }
  size_t messages_from_ = 0;

  static fs::path out_dir() {
    const fs::path d = fs::path(CLEAVE_BINARY_DIR) / "test_viz_headless_out";
    fs::create_directories(d);
    return d;
  }
};

using RGB = std::array<int, 3>;

RGB pixel(const Image& im, int x, int y) {
  const size_t i = (static_cast<size_t>(y) * im.width + x) * 3;
  return {im.rgb[i], im.rgb[i + 1], im.rgb[i + 2]};
}

int colour_distance(const RGB& a, const RGB& b) {
  return std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])});
}

std::string str(const RGB& c) {
  return "(" + std::to_string(c[0]) + "," + std::to_string(c[1]) + "," + std::to_string(c[2]) + ")";
}

// Pixels of `im` within [x0,x1) x [y0,y1) whose colour is within tol of c.
int count_near(const Image& im, const RGB& c, int tol, int x0 = 0, int y0 = 0, int x1 = -1, int y1 = -1) {
  if (x1 < 0) x1 = im.width;
  if (y1 < 0) y1 = im.height;
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      if (colour_distance(pixel(im, x, y), c) <= tol) ++n;
  return n;
}

// The gradient field: column i, row j (top first) -> (4i, 5j, 100).
constexpr int kFieldW = 64, kFieldH = 48;
RGB field_colour(int i, int j) { return {4 * i, 5 * j, 100}; }

Image gradient_field() {
  Image im;
  im.width = kFieldW;
  im.height = kFieldH;
  im.rgb.resize(kFieldW * kFieldH * 3);
  for (int j = 0; j < kFieldH; ++j)
    for (int i = 0; i < kFieldW; ++i) {
      const RGB c = field_colour(i, j);
      for (int k = 0; k < 3; ++k) im.rgb[(j * kFieldW + i) * 3 + k] = static_cast<uint8_t>(c[k]);
    }
  return im;
}

Frame2D gradient_frame() {
  Frame2D f;
  f.field = gradient_field();
  f.x0 = -1.0;
  f.x1 = 1.0;  // 2 x 1.5: the field's 4:3
  f.y0 = 0.5;
  f.y1 = 2.0;
  f.background = {1, 1, 1};
  Polyline2D line;
  line.points = {{-0.8, 1.25}, {0.0, 1.25}, {0.8, 1.25}};
  line.colour = {1, 0, 1};
  line.width = 3;
  f.overlays.push_back(line);
  f.title = "Gradient test frame";
  f.time_stamp = "t = 1.25 ms";
  f.colorbar.title = "stress (MPa)";
  f.colorbar.min = -10;
  f.colorbar.max = 250;
  f.colorbar.table = {{0, 0, 255}, {0, 255, 255}, {0, 255, 0}, {255, 255, 0}, {255, 0, 0}};
  return f;
}

// Image pixel (x from left, y from top) showing model point (mx, my).
std::array<int, 2> model_to_pixel(const PixelRect& vp, const Frame2D& f, double mx, double my) {
  const double u = (mx - f.x0) / (f.x1 - f.x0), v = (f.y1 - my) / (f.y1 - f.y0);
  return {vp.x + static_cast<int>(std::floor(u * vp.width)), vp.y + static_cast<int>(std::floor(v * vp.height))};
}

Camera3D view(const std::string& preset) {
  Camera3D c;
  c.preset = preset;
  return c;
}

ColorBar no_colour_bar() {
  ColorBar c;
  c.show = false;
  return c;
}

}  // namespace

// --- 2D frame --------------------------------------------------------------------------------------

TEST_F(VizHeadless, Frame2DShowsFieldBackgroundOverlayTitleAndColourBar) {
  HeadlessContext ctx(640, 480);
  const Frame2D f = gradient_frame();
  const Image im = render_frame_2d(ctx, f);
  ASSERT_EQ(im.width, 640);
  ASSERT_EQ(im.height, 480);
  ASSERT_EQ(im.rgb.size(), 640u * 480u * 3u);
  write_png(out_dir() / "frame2d.png", im);

  const PixelRect vp = frame_2d_field_viewport(640, 480, f);
  ASSERT_GT(vp.width, 300);
  ASSERT_GT(vp.height, 200);
  EXPECT_NEAR(static_cast<double>(vp.width) / vp.height, 4.0 / 3.0, 0.02);
  EXPECT_GT(vp.y, 20) << "no title band";
  EXPECT_LT(vp.x + vp.width, 640 - 60) << "no colour bar band";

  // Field pixels: the centre of each sampled texel shows exactly that texel's colour.
  int checked = 0;
  for (int j = 1; j < kFieldH; j += 5)
    for (int i = 1; i < kFieldW; i += 7) {
      const double mx = f.x0 + (i + 0.5) / kFieldW * (f.x1 - f.x0);
      const double my = f.y1 - (j + 0.5) / kFieldH * (f.y1 - f.y0);
      if (std::abs(my - 1.25) < 0.1) continue;  // under the overlay
      const auto p = model_to_pixel(vp, f, mx, my);
      const RGB got = pixel(im, p[0], p[1]);
      EXPECT_LE(colour_distance(got, field_colour(i, j)), 2)
          << "texel (" << i << "," << j << ") at pixel (" << p[0] << "," << p[1] << "): got " << str(got)
          << ", expected " << str(field_colour(i, j));
      ++checked;
    }
  EXPECT_GT(checked, 50);
  // The field's corners sit at the viewport's corners (within a pixel).
  EXPECT_LE(colour_distance(pixel(im, vp.x + 1, vp.y + 1), field_colour(0, 0)), 2);
  EXPECT_LE(colour_distance(pixel(im, vp.x + vp.width - 2, vp.y + vp.height - 2), field_colour(63, 47)), 2);

  // Background outside the field.
  const RGB white{255, 255, 255};
  EXPECT_EQ(pixel(im, 1, im.height - 2), white);
  EXPECT_EQ(pixel(im, vp.x - 3 > 0 ? vp.x - 3 : 0, vp.y + vp.height / 2), white);
  EXPECT_EQ(pixel(im, vp.x + vp.width / 2, std::min(im.height - 1, vp.y + vp.height + 3)), white);

  // The overlay: magenta along y = 1.25 from x = -0.8 to 0.8 (within two pixel rows).
  const RGB magenta{255, 0, 255};
  for (double mx = -0.75; mx <= 0.751; mx += 0.125) {
    const auto p = model_to_pixel(vp, f, mx, 1.25);
    bool found = false;
    for (int dy = -2; dy <= 2 && !found; ++dy) found = colour_distance(pixel(im, p[0], p[1] + dy), magenta) <= 8;
    EXPECT_TRUE(found) << "no overlay colour near pixel (" << p[0] << "," << p[1] << ")";
  }
  // ...and not beyond its ends.
  const auto beyond = model_to_pixel(vp, f, 0.95, 1.25);
  for (int dy = -2; dy <= 2; ++dy) EXPECT_GT(colour_distance(pixel(im, beyond[0], beyond[1] + dy), magenta), 8);

  // Title: dark pixels in the middle of the title band.
  const int band_x0 = 320 - 60, band_x1 = 320 + 60;
  const int dark = count_near(im, {0, 0, 0}, 100, band_x0, 0, band_x1, vp.y);
  EXPECT_GT(dark, 30) << "no title text";

  // Colour bar: the table's end colours in the right band.
  const int band = vp.x + vp.width + 4;
  EXPECT_GT(count_near(im, {0, 0, 255}, 30, band, 0, 640, 480), 40);
  EXPECT_GT(count_near(im, {255, 0, 0}, 30, band, 0, 640, 480), 40);
  EXPECT_GT(count_near(im, {0, 0, 0}, 100, band, 0, 640, 480), 30) << "no colour bar labels";

  // Control: without a title (time stamp only) the middle of the title band is background.
  Frame2D g = f;
  g.title.clear();
  const Image im2 = render_frame_2d(ctx, g);
  EXPECT_EQ(frame_2d_field_viewport(640, 480, g).y, vp.y);
  EXPECT_EQ(count_near(im2, {0, 0, 0}, 100, band_x0, 0, band_x1, vp.y), 0);
  EXPECT_GT(count_near(im2, {0, 0, 0}, 100, 400, 0, 640, vp.y), 10) << "no time stamp";
  // The same frame again renders identically (renderers of the last frame are gone).
  const Image im3 = render_frame_2d(ctx, f);
  EXPECT_EQ(im3.rgb, im.rgb);
}

TEST_F(VizHeadless, Frame2DWithoutColourBarOrTitleUsesTheWholeWindow) {
  HeadlessContext ctx(300, 300);
  Frame2D f;
  f.field = gradient_field();
  f.x0 = 0;
  f.x1 = 1;
  f.y0 = 0;
  f.y1 = 1;  // square window, 4:3 pixels stretched
  f.background = {0, 0, 0};
  f.colorbar.show = false;
  const PixelRect vp = frame_2d_field_viewport(300, 300, f);
  EXPECT_EQ(vp.width, vp.height);
  EXPECT_GT(vp.width, 270);
  const Image im = render_frame_2d(ctx, f);
  EXPECT_EQ(pixel(im, 0, 0), (RGB{0, 0, 0}));
  const auto p = model_to_pixel(vp, f, (10 + 0.5) / kFieldW, 1 - (20 + 0.5) / kFieldH);
  EXPECT_LE(colour_distance(pixel(im, p[0], p[1]), field_colour(10, 20)), 2);
  Frame2D flat;
  flat.x0 = flat.x1 = 1;
  EXPECT_THROW(frame_2d_field_viewport(300, 300, flat), std::invalid_argument);
}

// --- 3D particles ----------------------------------------------------------------------------------

TEST_F(VizHeadless, Particles3DShowCubesInTheirColours) {
  std::vector<std::array<double, 3>> centres;
  std::vector<double> edge;
  std::vector<std::array<uint8_t, 3>> colours;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < 10; ++i) {
        centres.push_back({0.1 * i, 0.1 * j, 0.1 * k});
        edge.push_back(0.08);
        colours.push_back(i < 5 ? std::array<uint8_t, 3>{220, 40, 40} : std::array<uint8_t, 3>{40, 90, 220});
      }
  ASSERT_EQ(centres.size(), 400u);
  HeadlessContext ctx(480, 360);
  const std::array<double, 3> bg{0.1, 0.1, 0.1};
  const RGB bg_px{26, 26, 26};
  ColorBar cb;
  cb.title = "speed";
  cb.min = 1e-3;
  cb.max = 10;
  cb.log = true;

  const Image iso = render_particles_3d(ctx, centres, edge, colours, Camera3D{}, "Cubes", "t = 0", cb, bg);
  write_png(out_dir() / "particles_iso.png", iso);
  int non_bg = 0;
  for (int y = 0; y < iso.height; ++y)
    for (int x = 0; x < iso.width; ++x) non_bg += colour_distance(pixel(iso, x, y), bg_px) > 6;
  EXPECT_GT(non_bg, 10000);
  // Shaded, but the cube hues are there: red-dominant and blue-dominant pixels.
  int reddish = 0, bluish = 0;
  for (int y = 0; y < iso.height; ++y)
    for (int x = 0; x < iso.width; ++x) {
      const RGB c = pixel(iso, x, y);
      reddish += c[0] > 100 && c[0] > 3 * c[1] && c[0] > 3 * c[2];
      bluish += c[2] > 100 && c[2] > 2 * c[0] && c[2] > 2 * c[1];
    }
  EXPECT_GT(reddish, 1000);
  EXPECT_GT(bluish, 1000);

  // Looking straight down, the top faces face the headlight: their colours come through exactly.
  const Image xy = render_particles_3d(ctx, centres, edge, colours, view("xy"), "", "", no_colour_bar(), bg);
  EXPECT_GT(count_near(xy, {220, 40, 40}, 3), 5000);
  EXPECT_GT(count_near(xy, {40, 90, 220}, 3), 5000);

  for (const char* preset : {"xz", "yz"}) {
    const Image im = render_particles_3d(ctx, centres, edge, colours, view(preset), "", "", cb, bg);
    EXPECT_GT(count_near(im, {220, 40, 40}, 3) + count_near(im, {40, 90, 220}, 3), 2000) << preset;
  }
  Camera3D explicit_view;
  explicit_view.explicit_view = std::array<double, 9>{0.45, -3.0, 1.5, 0.45, 0.45, 0.15, 0, 0, 1};
  const Image ex = render_particles_3d(ctx, centres, edge, colours, explicit_view, "", "", cb, bg);
  int ex_non_bg = 0;
  for (int y = 0; y < ex.height; ++y)
    for (int x = 0; x < ex.width; ++x) ex_non_bg += colour_distance(pixel(ex, x, y), bg_px) > 6;
  EXPECT_GT(ex_non_bg, 3000);

  EXPECT_THROW(render_particles_3d(ctx, centres, {0.1}, colours, Camera3D{}, "", "", cb, bg), std::invalid_argument);
  EXPECT_THROW(render_particles_3d(ctx, centres, edge, colours, view("top"), "", "", cb, bg),
               std::invalid_argument);
  // No particles: just the background and annotations.
  const Image empty = render_particles_3d(ctx, {}, {}, {}, Camera3D{}, "", "", no_colour_bar(), bg);
  EXPECT_EQ(count_near(empty, bg_px, 0), empty.width * empty.height);
}

// --- plot ------------------------------------------------------------------------------------------

TEST_F(VizHeadless, PlotOfASine) {
  PlotSeries s;
  s.name = "sin(x)";
  for (int i = 0; i <= 200; ++i) {
    s.x.push_back(i * 0.05);
    s.y.push_back(std::sin(i * 0.05));
  }
  HeadlessContext ctx(640, 400);
  const Image im = render_plot(ctx, {s}, "A sine", "x", "sin x");
  write_png(out_dir() / "plot.png", im);
  ASSERT_EQ(im.width, 640);
  ASSERT_EQ(im.height, 400);
  const int total = im.width * im.height;
  const int white = count_near(im, {255, 255, 255}, 0);
  EXPECT_GT(white, total / 2) << "background should be white";
  EXPECT_LT(white, total - 2000) << "plot is (nearly) empty";
  EXPECT_GT(count_near(im, {31, 119, 180}, 40), 300) << "no line in the series colour";
  EXPECT_GT(count_near(im, {0, 0, 0}, 90), 200) << "no axis labels or title";
  // The curve goes up and down: series-coloured pixels in both the upper and lower thirds.
  EXPECT_GT(count_near(im, {31, 119, 180}, 40, 0, 0, 640, 160), 50);
  EXPECT_GT(count_near(im, {31, 119, 180}, 40, 0, 240, 640, 400), 50);
  PlotSeries bad{"bad", {1, 2}, {1}};
  EXPECT_THROW(render_plot(ctx, {bad}, "", "", ""), std::invalid_argument);
}

// --- files -----------------------------------------------------------------------------------------

TEST_F(VizHeadless, PngRoundTripIsBitExactAndJpegReads) {
  Image im;
  im.width = 37;
  im.height = 23;
  im.rgb.resize(37 * 23 * 3);
  std::mt19937 rng(7);
  for (auto& b : im.rgb) b = static_cast<uint8_t>(rng() & 0xff);
  const fs::path png = out_dir() / "roundtrip.png";
  write_png(png, im);
  const Image back = read_image(png);
  EXPECT_EQ(back.width, 37);
  EXPECT_EQ(back.height, 23);
  EXPECT_EQ(back.rgb, im.rgb);

  // Upper-case extension, a rendered frame.
  HeadlessContext ctx(200, 150);
  const Image frame = render_frame_2d(ctx, gradient_frame());
  const fs::path png2 = out_dir() / "ROUNDTRIP2.PNG";
  write_png(png2, frame);
  EXPECT_EQ(read_image(png2).rgb, frame.rgb);

  // JPEG (written here with VTK; lossy, so a smooth image and a tolerance).
  Image smooth = gradient_field();
  vtkNew<vtkImageData> data;
  data->SetDimensions(smooth.width, smooth.height, 1);
  data->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* dst = static_cast<uint8_t*>(data->GetScalarPointer());
  for (int j = 0; j < smooth.height; ++j)
    std::memcpy(dst + j * smooth.width * 3, &smooth.rgb[(smooth.height - 1 - j) * smooth.width * 3], smooth.width * 3);
  const fs::path jpg = out_dir() / "gradient.jpeg";
  vtkNew<vtkJPEGWriter> jw;
  jw->SetFileName(jpg.string().c_str());
  jw->SetInputData(data);
  jw->SetQuality(95);
  jw->Write();
  const Image j = read_image(jpg);
  ASSERT_EQ(j.width, smooth.width);
  ASSERT_EQ(j.height, smooth.height);
  int worst = 0;
  for (int y = 2; y < j.height - 2; ++y)
    for (int x = 2; x < j.width - 2; ++x) worst = std::max(worst, colour_distance(pixel(j, x, y), pixel(smooth, x, y)));
  EXPECT_LE(worst, 12);

  // Errors name the file.
  const fs::path missing = out_dir() / "no_such_image.png";
  try {
    read_image(missing);
    ADD_FAILURE() << "read_image of a missing file did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_image.png"), std::string::npos) << e.what();
  }
  const fs::path unwritable = out_dir() / "no_such_dir" / "x.png";
  try {
    write_png(unwritable, im);
    ADD_FAILURE() << "write_png into a missing directory did not throw";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("x.png"), std::string::npos) << e.what();
  }
  // vtkPNGWriter's own complaint reached the captured VTK output (so a GL error would too).
  EXPECT_NE(vtk_messages()->GetOutput().find("Unable to open file", messages_from_), std::string::npos);
  forget_vtk_messages();
  EXPECT_THROW(read_image(out_dir() / "frame.bmp"), std::runtime_error);
  Image broken{2, 2, {1, 2, 3}};
  EXPECT_THROW(write_png(out_dir() / "broken.png", broken), std::invalid_argument);
}

// --- several contexts ------------------------------------------------------------------------------

TEST_F(VizHeadless, ContextsOfDifferentSizesInSequenceTogetherAndResized) {
  const Frame2D f = gradient_frame();
  auto check = [&](const Image& im, int w, int h) {
    ASSERT_EQ(im.width, w);
    ASSERT_EQ(im.height, h);
    ASSERT_EQ(im.rgb.size(), static_cast<size_t>(w) * h * 3);
    const PixelRect vp = frame_2d_field_viewport(w, h, f);
    const auto p = model_to_pixel(vp, f, f.x0 + (30 + 0.5) / kFieldW * 2.0, f.y1 - (10 + 0.5) / kFieldH * 1.5);
    EXPECT_LE(colour_distance(pixel(im, p[0], p[1]), field_colour(30, 10)), 2) << w << "x" << h;
    EXPECT_EQ(pixel(im, 0, h - 1), (RGB{255, 255, 255})) << w << "x" << h;
  };
  // In sequence, each destroyed before the next.
  const std::array<std::array<int, 2>, 4> sizes{{{320, 240}, {500, 420}, {256, 256}, {800, 450}}};
  for (const auto& s : sizes) {
    HeadlessContext ctx(s[0], s[1]);
    check(render_frame_2d(ctx, f), s[0], s[1]);
  }
  // Two alive at once, used alternately.
  HeadlessContext a(400, 300), b(240, 320);
  const Image a1 = render_frame_2d(a, f);
  const Image b1 = render_frame_2d(b, f);
  const Image a2 = render_frame_2d(a, f);
  check(a1, 400, 300);
  check(b1, 240, 320);
  EXPECT_EQ(a1.rgb, a2.rgb);
  // Resized in place.
  a.resize(360, 360);
  EXPECT_EQ(a.width(), 360);
  check(render_frame_2d(a, f), 360, 360);
  a.resize(400, 300);
  EXPECT_EQ(render_frame_2d(a, f).rgb, a1.rgb);
  // Moved.
  HeadlessContext c = std::move(b);
  check(render_frame_2d(c, f), 240, 320);
  EXPECT_THROW(HeadlessContext(0, 10), std::invalid_argument);
}

// --- no X ------------------------------------------------------------------------------------------

TEST_F(VizHeadless, RendersThroughOSMesaWithoutAnyXConnection) {
  ASSERT_EQ(std::getenv("DISPLAY"), nullptr);
  // The guard is in effect: the process-wide XOpenDisplay (what VTK's libraries call) is ours.
  EXPECT_EQ(dlsym(RTLD_DEFAULT, "XOpenDisplay"), reinterpret_cast<void*>(&XOpenDisplay));
  EXPECT_EQ(dlsym(RTLD_DEFAULT, "xcb_connect"), reinterpret_cast<void*>(&xcb_connect));
  const int sockets_before = count_open_sockets();
  {
    HeadlessContext ctx(128, 96);
    const Image im = render_frame_2d(ctx, gradient_frame());
    EXPECT_EQ(im.width, 128);
    const std::string info = ctx.gl_info();
    EXPECT_NE(info.find("Mesa"), std::string::npos) << info;
    std::cout << info << "\n";
    EXPECT_STREQ(ctx.window()->GetClassName(), "vtkGenericOpenGLRenderWindow");
  }
  EXPECT_EQ(count_open_sockets(), sockets_before) << "rendering opened a socket";
  EXPECT_EQ(g_x_connect_attempts, 0);
}

// --- many frames -----------------------------------------------------------------------------------

namespace {
long resident_kib() {
  FILE* f = std::fopen("/proc/self/statm", "r");
  long pages = 0, resident = 0;
  if (f) {
    if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
    std::fclose(f);
  }
  return resident * (sysconf(_SC_PAGESIZE) / 1024);
}
}  // namespace

// A movie renders hundreds of frames through one context: each frame's renderers, textures and
// buffers must be released, so memory stays flat.
TEST_F(VizHeadless, ManyFramesInOneContextDoNotAccumulate) {
  HeadlessContext ctx(1280, 720);
  Frame2D f = gradient_frame();
  std::vector<long> rss;
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < 60; ++k) {
    f.time_stamp = "t = " + std::to_string(k) + " ms";
    f.overlays[0].points[1][1] = 1.0 + 0.01 * k;
    const Image im = render_frame_2d(ctx, f);
    ASSERT_EQ(im.width, 1280);
    rss.push_back(resident_kib());
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() / 60;
  std::cout << "1280x720 frame: " << ms << " ms; resident " << rss[10] / 1024 << " -> " << rss.back() / 1024
            << " MiB\n";
  EXPECT_LT(rss.back() - rss[10], 40 * 1024) << "memory grows with every frame";

  // ...and so does making and dropping contexts (one per frame size, say).
  long after_first = 0;
  for (int k = 0; k < 25; ++k) {
    HeadlessContext c(320 + 8 * k, 240);
    const Image im = render_particles_3d(c, {{0, 0, 0}, {1, 0, 0}}, {0.5, 0.5}, {{255, 0, 0}, {0, 0, 255}},
                                         Camera3D{}, "cubes", "", ColorBar{}, {1, 1, 1});
    ASSERT_EQ(im.width, 320 + 8 * k);
    if (k == 4) after_first = resident_kib();
  }
  std::cout << "contexts: resident " << after_first / 1024 << " -> " << resident_kib() / 1024 << " MiB\n";
  EXPECT_LT(resident_kib() - after_first, 40 * 1024) << "memory grows with every context";
}
