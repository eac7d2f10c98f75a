// The parts of a figure (issue 15, "Figures"): time stamps in µs, colour-bar names and round ticks,
// scale bars, smooth outlines that follow a body's boundary rather than its particles' staircase,
// and stress smoothing that removes MPM's cell-crossing checkerboard and keeps linear fields. The
// figures themselves, through the command line: test_viz_figures.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "viz/job/colour_scale.hpp"
#include "viz/raster/rasterize.hpp"
#include "viz/raster/smooth.hpp"
#include "viz/render/ticks.hpp"

namespace cleave::viz {
namespace {

// A 2D lattice frame of spacing s (particles whose centres satisfy inside(x, y)), with "size".
template <class Inside>
ParticleFrame lattice(double s, int n, Inside inside) {
  ParticleFrame f;
  for (int j = -n; j < n; ++j)
    for (int i = -n; i < n; ++i) {
      const double x = (i + 0.5) * s, y = (j + 0.5) * s;
      if (!inside(x, y)) continue;
      f.x.push_back({x, y, 0});
      f.arrays["size"].values.push_back(s);
    }
  return f;
}

// --- what a figure carries --------------------------------------------------------------------------

TEST(RenderFigureText, TimeStampsAreInMicrosecondsWithTheMicroSign) {
  EXPECT_EQ(format_time(3.0e-5), "t = 30.0 \xC2\xB5s");
  EXPECT_EQ(format_time(2.5e-3), "t = 2.5000 ms");
}

TEST(RenderFigureText, ColourBarsNameTheQuantityAndItsUnit) {
  EXPECT_EQ(field_label("von_mises"), "von Mises stress (MPa)");
  EXPECT_EQ(field_label("sxy"), "shear stress xy (MPa)");
  EXPECT_EQ(field_label("|v|"), "speed (m/s)");
  EXPECT_EQ(field_label("uy"), "displacement y (mm)");
  EXPECT_EQ(field_label("mass"), "mass");
}

TEST(RenderFigureText, ColourBarTicksAreRoundNumbersInOneTwoFiveSteps) {
  EXPECT_EQ(nice_ticks(2.15, 130), (std::vector<double>{20, 40, 60, 80, 100, 120}));
  EXPECT_EQ(nice_ticks(-66.2, 66.2), (std::vector<double>{-60, -40, -20, 0, 20, 40, 60}));
  EXPECT_EQ(nice_ticks(0, 10), (std::vector<double>{0, 2, 4, 6, 8, 10}));
  for (const auto& [lo, hi] : {std::pair{0.013, 0.0271}, {-3.3e6, 1.7e6}, {99.1, 99.9}, {1e-9, 7e-9}}) {
    const auto t = nice_ticks(lo, hi);
    ASSERT_GE(t.size(), 3u) << lo << " " << hi;
    ASSERT_LE(t.size(), 7u) << lo << " " << hi;
    const double step = t[1] - t[0], mant = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
    EXPECT_TRUE(std::fabs(mant - 1) < 1e-6 || std::fabs(mant - 2) < 1e-6 || std::fabs(mant - 5) < 1e-6) << step;
    for (double v : t) {
      EXPECT_GE(v, lo - 1e-12 * std::fabs(lo));
      EXPECT_LE(v, hi + 1e-12 * std::fabs(hi));
      EXPECT_NEAR(v / step, std::round(v / step), 1e-6) << v;
    }
  }
  EXPECT_EQ(log_ticks(0.5, 2000), (std::vector<double>{1, 10, 100, 1000}));
  EXPECT_EQ(format_tick(0.30000000000000004, 0.1), "0.3");
  EXPECT_EQ(format_tick(-1e-17, 0.1), "0");
}

TEST(RenderFigureText, ScaleBarsAreRoundLengthsWithTheirUnit) {
  // 0.1 mm per pixel, at most 300 pixels: 30 mm -> 20 mm.
  const ScaleBar a = nice_scale_bar(1e-4, 300);
  EXPECT_DOUBLE_EQ(a.length, 0.02);
  EXPECT_EQ(a.label, "20 mm");
  EXPECT_EQ(nice_scale_bar(1e-6, 600).label, "500 \xC2\xB5m");
  EXPECT_EQ(nice_scale_bar(1e-2, 150).label, "1 m");
  EXPECT_EQ(nice_scale_bar(0, 100).length, 0.0);
}

// --- smooth outlines --------------------------------------------------------------------------------

// Radial deviation of a rasterized disk's outline from the circle, sampled at 720 angles: mean and
// RMS about the mean, in spacings.
std::array<double, 2> outline_deviation(const Raster& r, double R, double s) {
  const View& v = r.view;
  double sum = 0, sum2 = 0;
  const int na = 720;
  for (int k = 0; k < na; ++k) {
    const double a = 2 * std::numbers::pi * (k + 0.5) / na;
    double last = 0;
    for (double rr = R - 3 * s; rr < R + 3 * s; rr += 0.05 * v.pixel_width()) {
      const int i = int(std::floor((rr * std::cos(a) - v.x0) / v.pixel_width()));
      const int j = int(std::floor((v.y1 - rr * std::sin(a)) / v.pixel_height()));
      if (i >= 0 && j >= 0 && i < v.width && j < v.height && r.covered[std::size_t(j) * v.width + i]) last = rr;
    }
    const double d = (last - R) / s;
    sum += d, sum2 += d * d;
  }
  const double mean = sum / na;
  return {mean, std::sqrt(std::max(0.0, sum2 / na - mean * mean))};
}

TEST(RasterSmoothOutlines, ADisksOutlineFollowsTheCircleNotTheParticlesStaircase) {
  const double s = 0.5, R = 15;  // the five-disk scene's disks: 60 particles across
  const ParticleFrame f = lattice(s, 32, [&](double x, double y) { return x * x + y * y < R * R; });
  const View v = fit_view(f, 1200, 1200, std::nullopt, 1.0, 0.15);  // ~15 pixels per spacing
  const std::vector<double> one(f.x.size(), 1.0);
  const Raster raw = rasterize_2d(f, v, one, 1);
  RasterOptions ro;
  ro.smooth_outline = true;
  const Raster smooth = rasterize_2d(f, v, one, 1, ro);
  const auto dr = outline_deviation(raw, R, s), ds = outline_deviation(smooth, R, s);
  std::printf("outline about the circle (spacings): squares mean %.3f RMS %.3f; smooth mean %.3f RMS %.3f\n", dr[0],
              dr[1], ds[0], ds[1]);
  EXPECT_GT(dr[1], 0.2) << "the squares' staircase";
  EXPECT_LT(ds[1], 0.1) << "the smooth outline";
  EXPECT_LT(std::fabs(ds[0]), 0.1) << "on the circle, not inside or outside it";
  // Inside, values and owners are those of the raw raster; every covered pixel has an owner.
  for (std::size_t q = 0; q < smooth.covered.size(); ++q) {
    if (smooth.covered[q]) {
      ASSERT_GE(smooth.owner[q], 0);
    }
    if (raw.covered[q] && smooth.covered[q]) {
      ASSERT_EQ(smooth.values[q], raw.values[q]);
    }
  }
  // The edge distance changes sign across the outline.
  ASSERT_EQ(smooth.edge.size(), smooth.covered.size());
  for (std::size_t q = 0; q < smooth.edge.size(); ++q) ASSERT_EQ(smooth.edge[q] >= 0, smooth.covered[q] == 1) << q;
}

TEST(RasterSmoothOutlines, ARectangleKeepsItsCornersAndAThinStripAndAGapOfThreeSpacingsStay) {
  const double s = 1.0;
  // A 20 x 10 block, a strip one particle thick 4 spacings above it, a second block 3 spacings to
  // the right.
  ParticleFrame f = lattice(s, 40, [&](double x, double y) {
    const bool block = x > 0 && x < 20 && y > 0 && y < 10, strip = x > 0 && x < 20 && y > 14 && y < 15;
    const bool other = x > 23 && x < 33 && y > 0 && y < 10;
    return block || strip || other;
  });
  const View v = fit_view(f, 1000, 600, std::nullopt, 1.0);
  const std::vector<double> one(f.x.size(), 1.0);
  RasterOptions ro;
  ro.smooth_outline = true;
  const Raster raw = rasterize_2d(f, v, one, 1), smooth = rasterize_2d(f, v, one, 1, ro);
  auto at = [&](const Raster& r, double x, double y) {
    const int i = int(std::floor((x - v.x0) / v.pixel_width())), j = int(std::floor((v.y1 - y) / v.pixel_height()));
    return r.covered[std::size_t(j) * v.width + i] == 1;
  };
  // Away from the gap the coverage is the squares' own (less the 2 % slack of the footprint test on
  // straight edges): straight edges, sharp corners, the strip.
  std::size_t differ = 0, raw_n = 0;
  for (int j = 0; j < v.height; ++j)
    for (int i = 0; i < v.width; ++i) {
      const double x = v.pixel_x(i);
      const std::size_t q = std::size_t(j) * v.width + i;
      raw_n += raw.covered[q];
      if (x < 19 || x > 24) differ += raw.covered[q] != smooth.covered[q];
    }
  EXPECT_LT(differ, raw_n / 100);
  for (const auto& [x, y] : {std::pair{0.05, 0.05}, {19.95, 0.05}, {0.05, 9.95}, {19.95, 9.95}, {32.95, 9.95}})
    EXPECT_TRUE(at(smooth, x, y)) << "corner at " << x << ", " << y;
  for (double x = 0.05; x < 20; x += 0.5) EXPECT_TRUE(at(smooth, x, 14.5)) << "strip at x = " << x;
  // The gap stays open, narrowed by at most 0.15 spacings on each side (the blocks' blurred
  // footprints reach across it a little).
  for (double y = 0.5; y < 10; y += 0.5) {
    EXPECT_FALSE(at(smooth, 20.15, y)) << y;
    EXPECT_FALSE(at(smooth, 22.85, y)) << y;
  }
}

// --- stress smoothing -------------------------------------------------------------------------------

TEST(RasterStressSmoothing, RemovesACellCheckerboardAndKeepsLinearFieldsExactly) {
  const double s = 1.0;
  const ParticleFrame f = lattice(s, 20, [](double x, double y) { return x * x + y * y < 18 * 18; });
  std::vector<double> linear(f.x.size()), noisy(f.x.size());
  double noise_before = 0, noise_after = 0;
  for (std::size_t p = 0; p < f.x.size(); ++p) {
    linear[p] = 3 + 2 * f.x[p][0] - 0.5 * f.x[p][1];
    // A checkerboard of 2 x 2 particle cells, as particles crossing cells leave it.
    const int cx = int(std::floor(f.x[p][0] / (2 * s))), cy = int(std::floor(f.x[p][1] / (2 * s)));
    noisy[p] = linear[p] + ((cx + cy) % 2 == 0 ? 1.0 : -1.0);
  }
  SmoothSettings st;
  st.sigma = 1.5;
  const auto lin = smooth_particle_values(f, linear, 1, st), sm = smooth_particle_values(f, noisy, 1, st);
  for (std::size_t p = 0; p < f.x.size(); ++p) {
    ASSERT_NEAR(lin[p], linear[p], 1e-9) << "linear fields are kept, also at the edge";
    noise_before += std::pow(noisy[p] - linear[p], 2);
    if (std::hypot(f.x[p][0], f.x[p][1]) < 12) noise_after += std::pow(sm[p] - linear[p], 2);
  }
  std::printf("checkerboard RMS: %.3f before, %.3f after (inside r < 12)\n", std::sqrt(noise_before / f.x.size()),
              std::sqrt(noise_after / f.x.size()));
  EXPECT_LT(noise_after, 0.01 * noise_before);
}

TEST(RasterStressSmoothing, NothingIsAveragedAcrossACrackPathOrAnOpenedGap) {
  const double s = 1.0;
  ParticleFrame f = lattice(s, 10, [](double, double) { return true; });
  std::vector<double> v(f.x.size());
  for (std::size_t p = 0; p < f.x.size(); ++p) v[p] = f.x[p][1] > 0 ? 5.0 : -5.0;
  SmoothSettings st;
  st.barriers = {{-20, 0, 20, 0}};  // a crack along the whole block: two pieces
  const auto a = smooth_particle_values(f, v, 1, st);
  for (std::size_t p = 0; p < f.x.size(); ++p) ASSERT_NEAR(a[p], v[p], 1e-12);
  // Without the barrier but with the halves a spacing apart: an opened crack.
  ParticleFrame g = f;
  for (auto& x : g.x) x[1] += x[1] > 0 ? 0.5 : -0.5;
  const auto b = smooth_particle_values(g, v, 1, SmoothSettings{});
  for (std::size_t p = 0; p < g.x.size(); ++p) ASSERT_NEAR(b[p], v[p], 1e-12);
}

}  // namespace
}  // namespace cleave::viz
