// Renderer validation (issue: renderer, validation tests 1, 2 and 5): Brazilian disk fringes against
// the closed form of validation.md section 7, analytic particles and a simulated MPM disk, and the
// fringe-order RMS of digitised points.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <numbers>

#include "libmpm/mpm/mpm_method.hpp"
#include "libmpm/mpm/mpm_scene.hpp"
#include "libmpm/method/method.hpp"
#include "libmpm/method/run_loop.hpp"
#include "viz/job/render_job.hpp"

namespace cleave::viz {
namespace {

namespace fs = std::filesystem;
constexpr double kR = 0.02, kT = 0.005, kFs = 7000.0;  // m, m, N/m per fringe (polycarbonate ~7 N/mm)

// A disk of particles on a square lattice of spacing h, each carrying the closed-form stress for load P.
ParticleFrame analytic_disk(double P, double h) {
  ParticleFrame f;
  f.dim = 2;
  PointArray stress{6, {}}, size{1, {}};
  const int n = int(std::ceil(kR / h));
  for (int i = -n; i < n; ++i)
    for (int j = -n; j < n; ++j) {
      const double x = (i + 0.5) * h, y = (j + 0.5) * h;
      if (x * x + y * y > kR * kR) continue;
      f.x.push_back({x, y, 0});
      const Stress2 s = brazilian_disk_stress(x, y, kR, P, kT);
      for (double v : {s.xx, s.yy, 0.0, s.xy, 0.0, 0.0}) stress.values.push_back(v);
      size.values.push_back(h);
    }
  f.arrays["stress"] = stress;
  f.arrays["size"] = size;
  return f;
}

PhotoelasticSettings dark_field() {
  PhotoelasticSettings s;
  s.mode = Polariscope::CircularDark;
  s.thickness = kT;
  s.fringe_constant = kFs;
  return s;
}

double pixel_x(const View& v, int i) { return v.x0 + (i + 0.5) * (v.x1 - v.x0) / v.width; }
double pixel_y(const View& v, int j) { return v.y1 - (j + 0.5) * (v.y1 - v.y0) / v.height; }

// Dark fringes crossed along the vertical diameter, |y| < ymax: runs of samples darker than 0.1.
int dark_fringes_along_diameter(const std::function<double(double)>& I, double ymax, int samples) {
  int count = 0;
  bool dark = false;
  for (int k = 0; k <= samples; ++k) {
    const bool d = I(-ymax + 2 * ymax * k / samples) < 0.1;
    if (d && !dark) ++count;
    dark = d;
  }
  return count;
}

// Validation 1: analytic particles rendered in dark field against the per-pixel analytic image.
TEST(BrazilianDisk, AnalyticParticlesMatchThePerPixelImage) {
  unsetenv("DISPLAY");
  const double P = 400.0;  // N: ~4.6 fringes at the centre, ~10 along the diameter to 0.8 R
  const ParticleFrame f = analytic_disk(P, 2e-4);  // 200 particles across the diameter
  RenderOptions o;
  o.fringes = true;
  o.photo = dark_field();
  o.smooth = 0;  // the interpolation itself; the stress smoothing's cost on this field is below
  const View v = fit_view(f, 600, 600, std::nullopt, 1.0);
  ColorBar bar;
  const Image img = field_image(f, v, o, bar);
  // Correlation over the disk, r < 0.9 R (closer to the load points the fringes are finer than a pixel).
  auto correlation = [&](const Image& im) {
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    std::size_t n = 0;
    for (int j = 0; j < v.height; ++j)
      for (int i = 0; i < v.width; ++i) {
        const double x = pixel_x(v, i), y = pixel_y(v, j);
        if (x * x + y * y > 0.81 * kR * kR) continue;
        const Stress2 s = brazilian_disk_stress(x, y, kR, P, kT);
        const double a = intensity(s.xx, s.yy, s.xy, o.photo);
        const double b = im.rgb[3 * (std::size_t(j) * v.width + i)] / 255.0;
        sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b, ++n;
      }
    const double N = double(n);
    return (sab / N - sa / N * sb / N) / std::sqrt((saa / N - sa * sa / N / N) * (sbb / N - sb * sb / N / N));
  };
  const double corr = correlation(img);
  std::printf("dark-field correlation (r < 0.9 R): %.5f\n", corr);
  EXPECT_GE(corr, 0.99);
  // The default stress smoothing (1.5 spacings, for MPM's cell-crossing noise) on this noise-free
  // field: the fringes stay, a little softer where they are finest.
  RenderOptions os = o;
  os.smooth = RenderOptions{}.smooth;
  const double corr_smooth = correlation(field_image(f, v, os, bar));
  std::printf("dark-field correlation (r < 0.9 R) with the default smoothing: %.5f\n", corr_smooth);
  EXPECT_GE(corr_smooth, 0.98);
  // Fringe count along the vertical diameter, |y| < 0.8 R: rendered image against the closed form.
  const double ymax = 0.8 * kR;
  auto rendered = [&](double y) {
    const int i = v.width / 2, j = std::clamp(int((v.y1 - y) / (v.y1 - v.y0) * v.height), 0, v.height - 1);
    return img.rgb[3 * (std::size_t(j) * v.width + i)] / 255.0;
  };
  auto exact = [&](double y) {
    const Stress2 s = brazilian_disk_stress(pixel_x(v, v.width / 2), y, kR, P, kT);
    return intensity(s.xx, s.yy, s.xy, o.photo);
  };
  // One sample per image row for both, at the row's pixel centre.
  const int rows = int(2 * ymax / (v.y1 - v.y0) * v.height);
  const int nr = dark_fringes_along_diameter(rendered, ymax, rows), ne = dark_fringes_along_diameter(exact, ymax, rows);
  std::printf("dark fringes along the vertical diameter (|y| < 0.8 R): rendered %d, analytic %d\n", nr, ne);
  EXPECT_GT(ne, 4);
  EXPECT_EQ(nr, ne);
}

// Validation 5: digitised points of known fringe order give RMS ~ 0; a different load a larger RMS.
TEST(BrazilianDisk, DigitisedPointsRms) {
  const double P = 400.0;
  const ParticleFrame f = analytic_disk(P, 2e-4);
  const PhotoelasticSettings s = dark_field();
  std::vector<std::array<double, 3>> same, shifted;
  for (int k = 0; k < 40; ++k) {
    const double a = 2 * std::numbers::pi * k / 40, r = 0.6 * kR * (0.2 + 0.8 * (k % 5) / 4.0);
    const double x = r * std::cos(a), y = r * std::sin(a);
    const Stress2 e = brazilian_disk_stress(x, y, kR, P, kT);
    const double N = fringe_order(e.xx, e.yy, e.xy, s);
    same.push_back({x, y, N});
    const Stress2 e2 = brazilian_disk_stress(x, y, kR, 1.2 * P, kT);  // another load
    shifted.push_back({x, y, fringe_order(e2.xx, e2.yy, e2.xy, s)});
  }
  std::size_t used = 0;
  const double rms_same = fringe_order_rms(f, s, same, &used);
  EXPECT_EQ(used, same.size());
  const double rms_shift = fringe_order_rms(f, s, shifted);
  std::printf("fringe-order RMS: matching points %.4f, points of a 20 %% larger load %.4f\n", rms_same, rms_shift);
  // Matching points differ only by the interpolation of a smooth field between particles 0.2 mm apart.
  EXPECT_LT(rms_same, 0.02);
  EXPECT_GT(rms_shift, 10 * rms_same);
  EXPECT_GT(rms_shift, 0.3);
}

// The dark-field fringe order of the last particle frame in `out` against the closed form of the disk
// under 800 N, per pixel of a 500 x 500 raster over r < 0.6 R: the RMS, and the pixels counted (n).
double last_frame_fringe_rms(const fs::path& out, std::size_t& n) {
  const auto entries = read_series(out);
  const ParticleFrame f = read_particle_frame(entries.back().file, entries.back().time);
  const View v = fit_view(f, 500, 500, std::nullopt, 1.0);
  const Raster r = stress_raster(f, v);
  const PhotoelasticSettings s = dark_field();
  double sum = 0;
  n = 0;
  for (int j = 0; j < v.height; ++j)
    for (int i = 0; i < v.width; ++i) {
      const double x = pixel_x(v, i), y = pixel_y(v, j);
      const std::size_t q = std::size_t(j) * v.width + i;
      if (x * x + y * y > 0.36 * kR * kR || !r.covered[q]) continue;
      const Stress2 e = brazilian_disk_stress(x, y, kR, 800.0, kT);
      const double d = fringe_order(r.values[3 * q], r.values[3 * q + 1], r.values[3 * q + 2], s) - fringe_order(e.xx, e.yy, e.xy, s);
      sum += d * d, ++n;
    }
  return std::sqrt(sum / n);
}

// Validation 2: a damped MPM disk in diametral compression (data/scenes/brazilian_disk.json: 800 N,
// 0.5 mm cells), per-pixel fringe order against the closed form within r < 0.6 R.
TEST(BrazilianDisk, SimulatedDiskMatchesTheClosedForm) {
  const fs::path out = fs::path(CLEAVE_BINARY_DIR) / "test_viz_brazilian";
  fs::remove_all(out);
  const nlohmann::json scene = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/brazilian_disk.json");
  Model<2> m = build_model<2>(scene);
  RunOptions ro;
  ro.out = out;
  run_model<2>(m, ro);
  std::size_t n = 0;
  const double rms = last_frame_fringe_rms(out, n);
  std::printf("simulated disk: fringe-order RMS vs closed form over r < 0.6 R (%zu pixels): %.4f\n", n, rms);
  EXPECT_GT(n, 10000u);
  EXPECT_LT(rms, 0.2);
}

// Validation 5 of the PEM issue (validation.md section 6): the same scene, brazilian_disk.json, run
// by each method ("method" set as `--set method=...` does), rendered as dark-field fringes and
// compared with the closed form as above: the fringe-order RMS over r < 0.6 R, and the wall time.
class BrazilianDiskByMethod : public ::testing::TestWithParam<const char*> {};

TEST_P(BrazilianDiskByMethod, FringesMatchTheClosedFormWithinAFifthOfAFringe) {
  const std::string method = GetParam();
  const fs::path out = fs::path(CLEAVE_BINARY_DIR) / ("test_viz_brazilian_" + method);
  fs::remove_all(out);
  nlohmann::json scene = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/brazilian_disk.json");
  scene["method"] = method;
  RunOptions ro;
  ro.out = out;
  const auto summary = run_method<2>(*build_method<2>(scene), ro);
  std::size_t n = 0;
  const double rms = last_frame_fringe_rms(out, n);
  std::printf("%s: fringe-order RMS vs closed form over r < 0.6 R (%zu pixels): %.4f; %ld steps, %.1f s wall\n",
              method.c_str(), n, rms, summary.steps, summary.wall_s);
  EXPECT_GT(n, 10000u);
  EXPECT_LT(rms, 0.2);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, BrazilianDiskByMethod, ::testing::Values("peridynamics", "pem"));

}  // namespace
}  // namespace cleave::viz
