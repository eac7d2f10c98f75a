// The renderer's command line: cleave render / compare / plot on a small run, with DISPLAY unset.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <unistd.h>

#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include "cli_support.hpp"
#include "libmpm/io/pvd_writer.hpp"
#include "libmpm/io/vtu_writer.hpp"
#include "viz/job/render_job.hpp"

namespace cleave::viz {
namespace {

namespace fs = std::filesystem;
using test::fresh_dir;
constexpr auto& run = test::run_headless;  // `cleave ARGS` with DISPLAY unset (cli_support.hpp)

class RenderCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // CTest runs each test of this suite in its own process, concurrently: one directory per process.
    dir_ = fresh_dir(fs::path(CLEAVE_BINARY_DIR) / ("test_viz_cli_" + std::to_string(getpid())));
    // The Brazilian disk at 1 mm cells, a short damped run: ~1 300 particles, 7 frames.
    const auto r = run(std::string("run ") + CLEAVE_SOURCE_DIR "/data/scenes/brazilian_disk.json --quiet --threads 1 " +
                           "--set resolution=1 --set time.end=0.3 --out " + (dir_ / "disk").string(),
                       dir_);
    ASSERT_EQ(r.code, 0) << r.err;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static fs::path dir_;
};
fs::path RenderCli::dir_;

TEST_F(RenderCli, FringeFramesAndMovie) {
  const fs::path images = dir_ / "fringes";
  const auto r = run("render " + (dir_ / "disk").string() + " --fringes dark --fringe-constant 7 --thickness 5 --size 320x240 " +
                         "--keep-size --images " + images.string() + " --movie movie.mp4 --fps 5 --title Disk",
                     dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  int pngs = 0;
  for (const auto& e : fs::directory_iterator(images)) pngs += e.path().extension() == ".png";
  EXPECT_EQ(pngs, 7);
  ASSERT_TRUE(fs::exists(images / "movie.mp4")) << "ffmpeg (Debian package) must be installed";
  EXPECT_GT(fs::file_size(images / "movie.mp4"), 1000u);
  const Image img = read_image(images / "fringes_000006.png");
  EXPECT_EQ(img.width, 320);
  EXPECT_EQ(img.height, 240);
}

TEST_F(RenderCli, FieldWhiteLightAndPlots) {
  const fs::path d = dir_ / "disk";
  auto r = run("render " + d.string() + " --frames last --field syy --colormap cividis --range -20,5 --size 300x300", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(d / "render" / "syy_000006.png"));  // frames are named by their index: 7 frames
  r = run("render " + d.string() + " --frames last --white-light --fringes dark --fringe-constant 7 --thickness 5 --size 300x300", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(d / "render" / "fringes_white_000006.png"));
  r = run("plot " + d.string() + " --size 400x300", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(d / "render" / "energy.png"));
}

TEST_F(RenderCli, BadOptionsExit2WithAReason) {
  const fs::path d = dir_ / "disk";
  for (const std::string a : {"--fringes sideways", "--fringes dark", "--size 10", "--frames every:0",
                               "--range 5,1", "--colormap rainbow --frames last", "--bogus"}) {
    const auto r = run("render " + d.string() + " " + a, dir_);
    EXPECT_EQ(r.code, 2) << a << ": " << r.err;
    EXPECT_FALSE(r.err.empty()) << a;
  }
  const auto r = run("render " + (dir_ / "nothing_here").string(), dir_);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("nothing_here"), std::string::npos) << r.err;
}

// compare: a "photo" made from the model itself through the same map agrees (NCC ~ 1); the same
// photo mapped 3 mm off does not.
TEST_F(RenderCli, ComparePhotoAndPoints) {
  const fs::path d = dir_ / "disk";
  const auto entries = read_series(d);
  const ParticleFrame f = read_particle_frame(entries.back().file, entries.back().time);
  RenderOptions o;
  o.fringes = true;
  o.photo.thickness = 0.005;
  o.photo.fringe_constant = 7000;
  o.background = {0, 0, 0};
  // Photo: 200 x 200 pixels of 0.2 mm, top-left corner at (-20, 20) mm.
  const View v{-0.02, -0.02, 0.02, 0.02, 200, 200};
  ColorBar bar;
  write_png(dir_ / "photo.png", field_image(f, v, o, bar));
  // Digitised points: the model's own fringe order at a few points.
  std::ofstream pts(dir_ / "points.txt");
  pts << "# x y N (mm)\n";
  const Raster r = stress_raster(f, v);
  for (int k = 0; k < 12; ++k) {
    const int i = 60 + 7 * k, j = 100;
    const std::size_t q = std::size_t(j) * v.width + i;
    pts << v.pixel_x(i) * 1e3 << " " << v.pixel_y(j) * 1e3 << " "
        << fringe_order(r.values[3 * q], r.values[3 * q + 1], r.values[3 * q + 2], o.photo) << "\n";
  }
  pts.close();
  const std::string common = "compare " + d.string() + " --photo " + (dir_ / "photo.png").string() +
                             " --frame last --fringes dark --fringe-constant 7 --thickness 5 --length-unit mm " +
                             "--points " + (dir_ / "points.txt").string() + " --out " + (dir_ / "cmp").string();
  auto good = run(common + " --map -20,20,0.2", dir_);
  ASSERT_EQ(good.code, 0) << good.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(good.out, m, std::regex("cross-correlation ([0-9.\\-]+)"))) << good.out;
  const double ncc = std::stod(m[1]);
  ASSERT_TRUE(std::regex_search(good.out, m, std::regex("RMS difference ([0-9.e\\-]+)"))) << good.out;
  const double rms = std::stod(m[1]);
  auto off = run(common + " --map -17,20,0.2", dir_);
  ASSERT_EQ(off.code, 0) << off.err;
  ASSERT_TRUE(std::regex_search(off.out, m, std::regex("cross-correlation ([0-9.\\-]+)")));
  const double ncc_off = std::stod(m[1]);
  std::printf("NCC aligned %.4f, 3 mm off %.4f; points RMS %.4f\n", ncc, ncc_off, rms);
  EXPECT_GT(ncc, 0.95);
  EXPECT_LT(ncc_off, ncc - 0.2);
  EXPECT_LT(rms, 0.05);
  EXPECT_TRUE(fs::exists(dir_ / "cmp_side_by_side.png"));
  EXPECT_TRUE(fs::exists(dir_ / "cmp_overlay.png"));
}

// Crack series as the crack module writes them: J/K plots, the opening profile, and crack
// polylines drawn over frames.
TEST_F(RenderCli, CrackPlotsAndOverlay) {
  const fs::path d = dir_ / "disk_cracked";
  fs::remove_all(d);
  fs::copy(dir_ / "disk", d, fs::copy_options::recursive);
  std::ofstream tips(d / "crack_tips.csv");
  tips << "time_s,crack,tip,x_m,y_m,speed_m_per_s,J1_J_per_m2,J2_J_per_m2,KI_Pa_sqrt_m,KII_Pa_sqrt_m\n";
  for (int k = 0; k <= 10; ++k) tips << k * 3e-5 << ",0,0,0.005,0,0," << 10 * k << ",0," << 1e5 * k << "," << 2e4 * k << "\n";
  tips.close();
  io::PointSet crack;
  crack.points = {-0.01, 0.0, 0, 0.0, 0.0, 0, 0.01, 0.0, 0};
  crack.arrays = {{"cod_normal", 1, {0.0, 2e-5, 0.0}}, {"cod_tangential", 1, {0.0, 1e-6, 0.0}}, {"crack", 1, {0, 0, 0}}};
  crack.polylines = {{0, 1, 2}};
  io::write_vtu(d / "cracks_000000.vtu", crack);
  io::PvdIndex pvd(d / "cracks.pvd");
  pvd.add(0.0, "cracks_000000.vtu");
  pvd.write();
  auto r = run("plot " + d.string() + " --size 400x300", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(d / "render" / "J.png"));
  EXPECT_TRUE(fs::exists(d / "render" / "K.png"));
  r = run("plot " + d.string() + " --cod 0 --size 400x300", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(d / "render" / "cod_profile.png"));
  r = run("render " + d.string() + " --frames first --field syy --colormap gray --size 400x400", dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const Image img = read_image(d / "render" / "syy_000000.png");
  std::size_t red = 0;
  for (std::size_t i = 0; i < img.rgb.size(); i += 3)
    red += img.rgb[i] > 180 && img.rgb[i + 1] < 80 && img.rgb[i + 2] < 80;
  EXPECT_GT(red, 50u) << "the crack polyline is drawn over the gray field";
}

// The plots find CSV columns by their names with units (time_s, J1_J_per_m2, KI_Pa_sqrt_m), and by
// the bare names of runs written before the columns carried units; a file with neither gives no plot
// (and `cleave plot` says there is nothing to plot).
TEST_F(RenderCli, PlotsFindCsvColumnsByTheirNamesWithUnitsOrTheOlderBareNames) {
  const fs::path d = dir_ / "csv_names";
  auto plot_with = [&](const std::string& header, bool speed, int code = 0) {
    fresh_dir(d);
    std::ofstream tips(d / "crack_tips.csv");
    tips << header << "\n";
    for (int k = 0; k <= 10; ++k)
      tips << k * 3e-5 << ",0,1,0.005,0," << (speed ? "0," : "") << 10 * k << ",0," << 1e5 * k << "," << 2e4 * k << "\n";
    tips.close();
    const auto r = run("plot " + d.string() + " --size 400x300", dir_);
    EXPECT_EQ(r.code, code) << r.err;
    return test::read_text(d / "render" / "K.png");
  };
  const std::string with_units =
      plot_with("time_s,crack,tip,x_m,y_m,speed_m_per_s,J1_J_per_m2,J2_J_per_m2,KI_Pa_sqrt_m,KII_Pa_sqrt_m", true);
  ASSERT_FALSE(with_units.empty()) << "no K.png from columns with units";
  EXPECT_TRUE(fs::exists(d / "render" / "J.png"));
  EXPECT_EQ(plot_with("time,crack,tip,x,y,J1,J2,KI,KII", false), with_units) << "the older names plot the same";
  plot_with("time_s,crack,tip,x_m,y_m,speed_m_per_s,A,B,C,D", true, 1);
  EXPECT_FALSE(fs::exists(d / "render" / "K.png"));
  EXPECT_FALSE(fs::exists(d / "render" / "J.png"));
}

// Frames written with output.compression = zlib and output.precision = float32 render as the
// default raw Float64 frames do (VTK's reader decodes them; float32 moves a pixel at most rarely).
TEST_F(RenderCli, RendersZlibFloat32FramesLikeRawFloat64Frames) {
  const fs::path d = dir_ / "disk_zlib_f32";
  fs::remove_all(d);
  auto r = run(std::string("run ") + CLEAVE_SOURCE_DIR "/data/scenes/brazilian_disk.json --quiet --threads 1 " +
                   "--set resolution=1 --set time.end=0.3 --set output.compression=zlib " +
                   "--set output.precision=float32 --out " + d.string(),
               dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string last = io::PvdIndex::load(d / "particles.pvd").entries().back().second;
  EXPECT_EQ(last, io::PvdIndex::load(dir_ / "disk" / "particles.pvd").entries().back().second);
  EXPECT_LT(fs::file_size(d / last), fs::file_size(dir_ / "disk" / last) / 2);
  const std::string opts = " --frames last --field von_mises --size 320x240";
  r = run("render " + d.string() + opts, dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  const fs::path ref = dir_ / "disk_raw_f64";
  fs::remove_all(ref);
  fs::copy(dir_ / "disk", ref, fs::copy_options::recursive);
  fs::remove_all(ref / "render");  // images of other tests in this process
  r = run("render " + ref.string() + opts, dir_);
  ASSERT_EQ(r.code, 0) << r.err;
  auto the_png = [](const fs::path& images) {  // the one image rendered, whatever its frame number
    for (const auto& e : fs::directory_iterator(images))
      if (e.path().extension() == ".png") return e.path();
    return fs::path();
  };
  const Image a = read_image(the_png(d / "render")), b = read_image(the_png(ref / "render"));
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i) differ += std::abs(int(a.rgb[i]) - int(b.rgb[i])) > 2;
  EXPECT_LT(differ, a.rgb.size() / 1000) << "values differing by more than 2 levels";
}

TEST(RenderCli3D, CubesAndCutPlane) {
  const fs::path dir = fresh_dir(fs::path(CLEAVE_BINARY_DIR) / "test_viz_cli_3d");
  std::ofstream(dir / "cube.json") << R"({"analysis": {"type": "3d"}, "grid": {"cell_size": 0.005},
    "materials": [{"name": "m", "type": "linear_elastic", "E": 1e9, "nu": 0.3, "density": 1000}],
    "bodies": [{"name": "b", "material": "m", "velocity": [0, -5, 0],
                "shape": {"type": "box", "min": [0, 0, 0], "max": [0.04, 0.02, 0.02]}}],
    "loads": [{"type": "velocity", "region": {"min": [0, -1, -1], "max": [0, 1, 1]}, "velocity": [0, 0, 0]}],
    "time": {"end": 2e-5}, "output": {"interval": 1e-5}})";
  auto r = run("run " + (dir / "cube.json").string() + " --quiet --threads 1 --out " + (dir / "out").string(), dir);
  ASSERT_EQ(r.code, 0) << r.err;
  r = run("render " + (dir / "out").string() + " --frames last --field von_mises --size 320x240", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "out" / "render" / "von_mises_000002.png"));  // the last of 3 frames
  r = run("render " + (dir / "out").string() + " --frames last --field '|v|' --view 100,80,120,20,10,10,0,1,0 --length-unit mm " +
              "--images " + (dir / "view").string() + " --size 320x240",
          dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "view" / "_v__000002.png"));
  r = run("render " + (dir / "out").string() + " --frames last --field sxx --cut-plane 20,10,10,0,0,1 --length-unit mm " +
              "--images " + (dir / "cut").string() + " --size 320x240",
          dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "cut" / "sxx_000002.png"));
  // A crack surface (two triangles across the bar at x = 20 mm) is drawn over the cubes.
  {
    vtkNew<vtkPoints> pts;
    for (auto p : {std::array<double, 3>{0.02, -0.001, -0.001}, {0.02, 0.021, -0.001}, {0.02, 0.021, 0.021}, {0.02, -0.001, 0.021}})
      pts->InsertNextPoint(p.data());
    vtkNew<vtkUnstructuredGrid> g;
    g->SetPoints(pts);
    vtkIdType t0[3] = {0, 1, 2}, t1[3] = {0, 2, 3};
    g->InsertNextCell(VTK_TRIANGLE, 3, t0);
    g->InsertNextCell(VTK_TRIANGLE, 3, t1);
    vtkNew<vtkXMLUnstructuredGridWriter> w;
    w->SetFileName((dir / "out" / "cracks_000000.vtu").c_str());
    w->SetInputData(g);
    ASSERT_EQ(w->Write(), 1);
    io::PvdIndex pvd(dir / "out" / "cracks.pvd");
    pvd.add(0.0, "cracks_000000.vtu");
    pvd.write();
  }
  r = run("render " + (dir / "out").string() + " --frames last --field von_mises --colormap gray --size 320x240 --images " +
              (dir / "cracked").string(),
          dir);
  ASSERT_EQ(r.code, 0) << r.err;
  const Image img = read_image(dir / "cracked" / "von_mises_000002.png");
  std::size_t red = 0;
  for (std::size_t i = 0; i < img.rgb.size(); i += 3) red += img.rgb[i] > 180 && img.rgb[i + 1] < 80 && img.rgb[i + 2] < 80;
  EXPECT_GT(red, 100u) << "the 3D crack surface is drawn";
  r = run("render " + (dir / "out").string() + " --frames last --fringes dark --fringe-constant 7", dir);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("cut plane"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace cleave::viz
