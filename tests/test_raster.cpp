// Reading particle series and turning particles into per-pixel fields (viz/raster): coverage
// without holes, gaps and opened cracks left empty, linear fields reproduced exactly, strain-
// deformed footprints, view fitting, frame selection, scalar names, 3D cuts, and speed.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "libmpm/io/point_set.hpp"
#include "libmpm/io/pvd_writer.hpp"
#include "libmpm/io/vtu_writer.hpp"
#include "viz/raster/rasterize.hpp"
#include "viz/raster/series.hpp"

namespace fs = std::filesystem;
using namespace cleave::viz;

namespace {

// A fresh directory per test case under GoogleTest's temporary directory.
fs::path test_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  fs::path d = fs::path(::testing::TempDir()) / "cleave_test_raster" /
               (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// Adds one particle (2D) with a size.
void add(ParticleFrame& f, double x, double y, double s) {
  f.x.push_back({x, y, 0.0});
  f.arrays["size"].values.push_back(s);
}

// nx x ny lattice of spacing s whose lower-left particle domain corner is (x0, y0).
ParticleFrame block(int nx, int ny, double s, double x0 = 0, double y0 = 0) {
  ParticleFrame f;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) add(f, x0 + (i + 0.5) * s, y0 + (j + 0.5) * s, s);
  return f;
}

void append(ParticleFrame& a, const ParticleFrame& b) {
  for (std::size_t p = 0; p < b.x.size(); ++p) add(a, b.x[p][0], b.x[p][1], b.arrays.at("size").values[p]);
}

std::size_t pix(const Raster& r, int i, int j) {
  return static_cast<std::size_t>(j) * static_cast<std::size_t>(r.view.width) + static_cast<std::size_t>(i);
}

std::size_t count_covered(const Raster& r) {
  return static_cast<std::size_t>(std::count(r.covered.begin(), r.covered.end(), uint8_t{1}));
}

std::vector<SeriesEntry> five_frames() {
  std::vector<SeriesEntry> s;
  for (int i = 0; i < 5; ++i) {
    std::string name = "frame_";
    name += std::to_string(i);
    name += ".vtu";
    s.push_back({0.1 * i, name});
  }
  return s;
}

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no exception)";
}

}  // namespace

TEST(Rasterize, DiskHasNoHolesAndNothingOutside) {
  const double R = 1.0, s = 0.02;
  ParticleFrame f;
  const int n = static_cast<int>(std::ceil(R / s));
  for (int j = -n; j < n; ++j)
    for (int i = -n; i < n; ++i) {
      const double x = (i + 0.5) * s, y = (j + 0.5) * s;
      if (x * x + y * y < R * R) add(f, x, y, s);
    }
  const View v = fit_view(f, 500, 400, std::nullopt, 1.0);
  const std::vector<double> val(f.x.size(), 1.0);
  const Raster r = rasterize_2d(f, v, val, 1);
  ASSERT_EQ(r.values.size(), 500u * 400u);
  std::size_t inside = 0;
  for (int j = 0; j < v.height; ++j)
    for (int i = 0; i < v.width; ++i) {
      const double x = v.pixel_x(i), y = v.pixel_y(j), rr = std::hypot(x, y);
      const std::size_t p = pix(r, i, j);
      if (rr < R - s) {
        ++inside;
        ASSERT_TRUE(r.covered[p]) << "hole at pixel " << i << "," << j;
        ASSERT_GE(r.owner[p], 0);
        ASSERT_NEAR(r.values[p], 1.0, 1e-14);
      }
      if (rr > R + s) {
        ASSERT_FALSE(r.covered[p]) << "pixel " << i << "," << j << " outside the disk is covered";
        ASSERT_EQ(r.owner[p], -1);
        ASSERT_TRUE(std::isnan(r.values[p]));
      }
    }
  EXPECT_GT(inside, 10000u);
  // The covered area is the disk's, to within the stair-stepped rim.
  const double area = count_covered(r) * v.pixel_width() * v.pixel_height();
  EXPECT_NEAR(area, std::numbers::pi * R * R, 2 * std::numbers::pi * R * s);
}

TEST(Rasterize, OwnerCoversItsPixel) {
  ParticleFrame f = block(7, 5, 0.1, -0.3, 0.2);
  const View v = fit_view(f, 123, 77, std::nullopt, 1.0);
  const Raster r = rasterize_2d(f, v, std::vector<double>(f.x.size(), 0.0), 1);
  for (int j = 0; j < v.height; ++j)
    for (int i = 0; i < v.width; ++i) {
      const int32_t o = r.owner[pix(r, i, j)];
      if (o < 0) continue;
      // Half a footprint (0.05) plus the 2 % edge slack of the coverage test (kInsideTol).
      EXPECT_LE(std::abs(v.pixel_x(i) - f.x[static_cast<std::size_t>(o)][0]), 0.05 * 1.04 + 1e-9);
      EXPECT_LE(std::abs(v.pixel_y(j) - f.x[static_cast<std::size_t>(o)][1]), 0.05 * 1.04 + 1e-9);
    }
}

TEST(Rasterize, GapOfThreeSpacingsStaysEmpty) {
  const double s = 0.05;
  const int N = 20;
  ParticleFrame f = block(N, N, s);
  append(f, block(N, N, s, N * s + 3 * s, 0.0));
  const View v = fit_view(f, 600, 200, std::nullopt, 1.0);
  const Raster r = rasterize_2d(f, v, std::vector<double>(f.x.size(), 2.0), 1);
  std::size_t gap = 0, solid = 0;
  for (int j = 0; j < v.height; ++j)
    for (int i = 0; i < v.width; ++i) {
      const double x = v.pixel_x(i), y = v.pixel_y(j);
      if (y <= 0.01 || y >= N * s - 0.01) continue;
      const bool c = r.covered[pix(r, i, j)];
      if (x > N * s + 1e-6 && x < N * s + 3 * s - 1e-6) {
        ++gap;
        EXPECT_FALSE(c) << "gap pixel " << i << "," << j << " covered";
      }
      if ((x > 0.01 && x < N * s - 0.01) || (x > N * s + 3 * s + 0.01 && x < 2 * N * s + 3 * s - 0.01)) {
        ++solid;
        EXPECT_TRUE(c) << "block pixel " << i << "," << j << " not covered";
      }
    }
  EXPECT_GT(gap, 1000u);
  EXPECT_GT(solid, 10000u);
}

// Two halves of a block moved apart: the opening shows as uncovered pixels and each side keeps
// its own value right up to the crack face (nothing smeared across).
TEST(Rasterize, OpeningCrackShowsGapAndIsNotSmeared) {
  const double s = 0.05;
  for (double opening : {1.0 * s, 0.3 * s}) {
    ParticleFrame f = block(20, 20, s, -0.5, -0.5);
    std::vector<double> val(f.x.size());
    for (std::size_t p = 0; p < f.x.size(); ++p) {
      const double side = f.x[p][1] > 0 ? 1.0 : -1.0;
      f.x[p][1] += side * 0.5 * opening;
      val[p] = side;
    }
    const View v = fit_view(f, 800, 800, std::nullopt, 1.0);
    ASSERT_LT(v.pixel_height(), 0.2 * opening);
    const Raster r = rasterize_2d(f, v, val, 1);
    std::size_t open_pixels = 0;
    for (int j = 0; j < v.height; ++j)
      for (int i = 0; i < v.width; ++i) {
        const double x = v.pixel_x(i), y = v.pixel_y(j);
        if (std::abs(x) > 0.5 - 0.01) continue;
        const std::size_t p = pix(r, i, j);
        // Each face's footprint reaches 2 % of a particle into the gap (kInsideTol in rasterize.cpp).
        if (std::abs(y) < 0.5 * opening - 0.02 * s - 1e-9) {
          ++open_pixels;
          EXPECT_FALSE(r.covered[p]) << "opening " << opening << ": pixel " << i << "," << j << " covered";
        } else if (r.covered[p]) {
          ASSERT_NEAR(r.values[p], y > 0 ? 1.0 : -1.0, 1e-14)
              << "opening " << opening << ": value smeared across the crack at y = " << y;
        }
      }
    EXPECT_GT(open_pixels, 1000u) << "opening " << opening;
  }
}

TEST(Rasterize, LinearFieldIsReproducedExactlyInside) {
  const double s = 0.037, X0 = -0.41, Y0 = 0.23;
  const int nx = 31, ny = 23;
  ParticleFrame f = block(nx, ny, s, X0, Y0);
  const double a = 1.7, b = -2.3, c = 0.9;
  std::vector<double> val(2 * f.x.size());
  for (std::size_t p = 0; p < f.x.size(); ++p) {
    val[2 * p] = a + b * f.x[p][0] + c * f.x[p][1];
    val[2 * p + 1] = -3.0 + 0.5 * f.x[p][0] - 4.0 * f.x[p][1];
  }
  for (bool with_size : {true, false}) {
    ParticleFrame g = f;
    if (!with_size) g.arrays.erase("size");  // spacing from the median nearest-neighbour distance
    const View v = fit_view(g, 417, 311, std::nullopt, 1.0);
    const Raster r = rasterize_2d(g, v, val, 2);
    ASSERT_EQ(r.k, 2);
    std::size_t checked = 0;
    for (int j = 0; j < v.height; ++j)
      for (int i = 0; i < v.width; ++i) {
        const double x = v.pixel_x(i), y = v.pixel_y(j);
        if (x < X0 + 1.5 * s || x > X0 + (nx - 1.5) * s || y < Y0 + 1.5 * s || y > Y0 + (ny - 1.5) * s) continue;
        const std::size_t p = pix(r, i, j);
        ASSERT_TRUE(r.covered[p]);
        const double e0 = a + b * x + c * y, e1 = -3.0 + 0.5 * x - 4.0 * y;
        ASSERT_NEAR(r.values[2 * p], e0, 1e-12 * std::max(1.0, std::abs(e0))) << i << "," << j;
        ASSERT_NEAR(r.values[2 * p + 1], e1, 1e-12 * std::max(1.0, std::abs(e1))) << i << "," << j;
        ++checked;
      }
    EXPECT_GT(checked, 50000u);
  }
}

TEST(Rasterize, StrainDeformsFootprints) {
  ParticleFrame f;
  add(f, 0.0, 0.0, 1.0);
  const View v{-2, -2, 2, 2, 400, 400};
  auto extent = [&](double exx, double eyy, double exy) {
    ParticleFrame g = f;
    g.arrays["strain"] = PointArray{6, {exx, eyy, 0.0, exy, 0.0, 0.0}};
    const Raster r = rasterize_2d(g, v, {5.0}, 1);
    int i0 = v.width, i1 = -1, j0 = v.height, j1 = -1;
    for (int j = 0; j < v.height; ++j)
      for (int i = 0; i < v.width; ++i)
        if (r.covered[pix(r, i, j)]) {
          i0 = std::min(i0, i); i1 = std::max(i1, i);
          j0 = std::min(j0, j); j1 = std::max(j1, j);
          EXPECT_NEAR(r.values[pix(r, i, j)], 5.0, 1e-14);
        }
    return std::array<double, 3>{(i1 - i0 + 1) * v.pixel_width(), (j1 - j0 + 1) * v.pixel_height(),
                                 static_cast<double>(count_covered(r))};
  };
  const auto e0 = extent(0, 0, 0), e1 = extent(0.2, 0, 0), e2 = extent(0.5, 0, 0), e3 = extent(0, -0.25, 0);
  // The coverage test accepts 2 % of a footprint edge on each side (kInsideTol in rasterize.cpp,
  // which closes slivers between differently strained neighbours): every deformed width + 0.04.
  const double slack = 0.04;
  EXPECT_NEAR(e0[0], 1.0 + slack, 0.011);
  EXPECT_NEAR(e0[1], 1.0 + slack, 0.011);
  EXPECT_NEAR(e0[2], 10000 * (1 + slack) * (1 + slack), 10000 * 0.03);
  EXPECT_NEAR(e1[0], 1.2 + slack * 1.2, 0.011);
  EXPECT_NEAR(e1[1], 1.0 + slack, 0.011);
  EXPECT_NEAR(e1[2], 12000 * (1 + slack) * (1 + slack), 12000 * 0.03);
  EXPECT_GT(e2[0], e1[0]);
  EXPECT_GT(e2[2], e1[2]);
  EXPECT_NEAR(e3[1], 0.75 + slack * 0.75, 0.011);
  // Shear makes a parallelogram: same area, larger bounding box.
  const auto es = extent(0, 0, 0.2);
  EXPECT_GT(es[0], 1.1);
  EXPECT_NEAR(es[2], 10000 * (1 - 0.04) * (1 + slack) * (1 + slack), 10000 * 0.03);  // det(I + eps) = 0.96
}

TEST(Rasterize, Errors) {
  ParticleFrame f = block(3, 3, 0.1);
  const View v{0, 0, 1, 1, 10, 10};
  EXPECT_THROW(rasterize_2d(f, v, std::vector<double>(5), 1), std::invalid_argument);
  EXPECT_THROW(rasterize_2d(f, v, {}, -1), std::invalid_argument);
  EXPECT_THROW(rasterize_2d(f, View{0, 0, 1, 1, 0, 10}, std::vector<double>(9), 1), std::invalid_argument);
  ParticleFrame g = f;
  g.dim = 3;
  EXPECT_THROW(rasterize_2d(g, v, std::vector<double>(9), 1), std::invalid_argument);
  // k = 0: coverage only.
  const Raster r = rasterize_2d(f, v, {}, 0);
  EXPECT_TRUE(r.values.empty());
  EXPECT_GT(count_covered(r), 0u);
  // No particles: nothing covered.
  const Raster e = rasterize_2d(ParticleFrame{}, v, {}, 2);
  EXPECT_EQ(e.values.size(), 200u);
  EXPECT_EQ(count_covered(e), 0u);
}

#ifdef _OPENMP
TEST(Rasterize, SameResultForAnyThreadCount) {
  ParticleFrame f = block(150, 120, 0.01);
  std::vector<double> val(f.x.size());
  for (std::size_t p = 0; p < f.x.size(); ++p) {
    f.x[p][0] += 0.003 * std::sin(37.0 * p);  // irregular, overlapping footprints
    f.x[p][1] += 0.003 * std::cos(11.0 * p);
    val[p] = std::sin(f.x[p][0] * 9) * std::cos(f.x[p][1] * 7);
  }
  const View v = fit_view(f, 640, 480, std::nullopt, 1.0);
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const Raster a = rasterize_2d(f, v, val, 1);
  omp_set_num_threads(4);
  const Raster b = rasterize_2d(f, v, val, 1);
  omp_set_num_threads(saved);
  EXPECT_EQ(a.owner, b.owner);
  EXPECT_EQ(a.covered, b.covered);
  ASSERT_EQ(a.values.size(), b.values.size());
  for (std::size_t i = 0; i < a.values.size(); ++i)
    if (!(std::isnan(a.values[i]) && std::isnan(b.values[i]))) {
      ASSERT_EQ(a.values[i], b.values[i]) << i;
    }
}
#endif

TEST(FitView, AspectRoiAndZoom) {
  ParticleFrame f;
  add(f, 0.0, 0.0, 0.1);
  add(f, 2.0, 1.0, 0.1);
  // Bodies: [-0.05, 2.05] x [-0.05, 1.05]; margin 0.
  View v = fit_view(f, 100, 100, std::nullopt, 1.0, 0.0);
  EXPECT_DOUBLE_EQ(v.pixel_width(), v.pixel_height());
  EXPECT_NEAR(v.x0, -0.05, 1e-12);
  EXPECT_NEAR(v.x1, 2.05, 1e-12);
  EXPECT_NEAR(0.5 * (v.y0 + v.y1), 0.5, 1e-12);
  EXPECT_NEAR(v.y1 - v.y0, 2.1, 1e-12);
  // Margin: 3 % of the larger side on every side.
  v = fit_view(f, 300, 100, std::nullopt, 1.0);
  EXPECT_NEAR(v.pixel_width(), v.pixel_height(), 1e-15);
  EXPECT_NEAR(v.y1 - v.y0, 1.1 + 2 * 0.03 * 2.1, 1e-12);
  EXPECT_NEAR(0.5 * (v.x0 + v.x1), 1.0, 1e-12);
  EXPECT_LE(v.x0, -0.05 - 0.03 * 2.1 + 1e-12);
  // Region of interest, widened to the aspect ratio.
  v = fit_view(f, 200, 100, std::array<double, 4>{0, 0, 1, 1}, 1.0);
  EXPECT_NEAR(v.x0, -0.5, 1e-12);
  EXPECT_NEAR(v.x1, 1.5, 1e-12);
  EXPECT_NEAR(v.y0, 0.0, 1e-12);
  EXPECT_NEAR(v.y1, 1.0, 1e-12);
  EXPECT_EQ(v.width, 200);
  EXPECT_EQ(v.height, 100);
  // Zoom about the window centre.
  v = fit_view(f, 200, 100, std::array<double, 4>{0, 0, 1, 1}, 4.0);
  EXPECT_NEAR(v.x0, 0.25, 1e-12);
  EXPECT_NEAR(v.x1, 0.75, 1e-12);
  EXPECT_NEAR(v.y0, 0.375, 1e-12);
  EXPECT_NEAR(v.y1, 0.625, 1e-12);
  // Pixel centres.
  const View u{0, 0, 2, 1, 4, 2};
  EXPECT_DOUBLE_EQ(u.pixel_x(0), 0.25);
  EXPECT_DOUBLE_EQ(u.pixel_x(3), 1.75);
  EXPECT_DOUBLE_EQ(u.pixel_y(0), 0.75);
  EXPECT_DOUBLE_EQ(u.pixel_y(1), 0.25);

  EXPECT_THROW(fit_view(f, 0, 100, std::nullopt, 1.0), std::invalid_argument);
  EXPECT_THROW(fit_view(f, 100, 100, std::nullopt, 0.0), std::invalid_argument);
  EXPECT_THROW(fit_view(f, 100, 100, std::array<double, 4>{1, 0, 0, 1}, 1.0), std::invalid_argument);
  EXPECT_THROW(fit_view(ParticleFrame{}, 100, 100, std::nullopt, 1.0), std::invalid_argument);
  EXPECT_NO_THROW(fit_view(ParticleFrame{}, 100, 100, std::array<double, 4>{0, 0, 1, 1}, 1.0));
}

TEST(SelectFrames, Specs) {
  const auto s = five_frames();
  using V = std::vector<std::size_t>;
  EXPECT_EQ(select_frames(s, "all"), (V{0, 1, 2, 3, 4}));
  EXPECT_EQ(select_frames(s, "every:2"), (V{0, 2, 4}));
  EXPECT_EQ(select_frames(s, "every:1"), (V{0, 1, 2, 3, 4}));
  EXPECT_EQ(select_frames(s, "every:7"), (V{0}));
  EXPECT_EQ(select_frames(s, "time:0.26"), (V{3}));
  EXPECT_EQ(select_frames(s, "time:-5"), (V{0}));
  EXPECT_EQ(select_frames(s, "time:1e9"), (V{4}));
  EXPECT_EQ(select_frames(s, "time:0.11"), (V{1}));
  EXPECT_EQ(select_frames(s, "last"), (V{4}));
  EXPECT_EQ(select_frames(s, "first"), (V{0}));
  EXPECT_EQ(select_frames(s, "index:2"), (V{2}));
  EXPECT_EQ(select_frames(s, "index:-1"), (V{4}));
  EXPECT_EQ(select_frames(s, " last "), (V{4}));
  EXPECT_EQ(select_frames({}, "all"), V{});
}

TEST(SelectFrames, Errors) {
  const auto s = five_frames();
  for (const char* bad : {"every:0", "every:-2", "every:x", "every", "index:5", "index:-6", "index:1.5",
                          "time:", "time:abc", "bogus", "", "lastt", "time:nan"}) {
    EXPECT_THROW(select_frames(s, bad), std::invalid_argument) << bad;
    const std::string msg = error_of([&] { select_frames(s, bad); });
    std::string quoted = "\"";
    quoted += bad;
    quoted += '"';
    EXPECT_NE(msg.find(quoted), std::string::npos) << msg;
    EXPECT_NE(msg.find("every:K"), std::string::npos) << msg;
  }
  EXPECT_NE(error_of([&] { select_frames(s, "index:9"); }).find("5 frame"), std::string::npos);
  EXPECT_THROW(select_frames({}, "last"), std::invalid_argument);
  EXPECT_THROW(select_frames({}, "time:1"), std::invalid_argument);
}

TEST(ScalarField, NamesAndErrors) {
  ParticleFrame f;
  f.x = {{0, 0, 0}, {1, 0, 0}};
  f.arrays["stress"] = PointArray{6, {1, 2, 0, 3, 0, 0, -4, 5, 0, 0.5, 0, 0}};
  f.arrays["strain"] = PointArray{6, {0.1, 0.2, 0, 0.3, 0, 0, 0.4, 0.5, 0, 0.6, 0, 0}};
  f.arrays["displacement"] = PointArray{3, {3, 4, 0, -1, 0, 0}};
  f.arrays["velocity"] = PointArray{3, {0, 0, 2, 1, 1, 1}};
  f.arrays["material"] = PointArray{1, {0, 1}};
  using V = std::vector<double>;
  EXPECT_EQ(scalar_field(f, "sxx"), (V{1, -4}));
  EXPECT_EQ(scalar_field(f, "syy"), (V{2, 5}));
  EXPECT_EQ(scalar_field(f, "szz"), (V{0, 0}));
  EXPECT_EQ(scalar_field(f, "sxy"), (V{3, 0.5}));
  EXPECT_EQ(scalar_field(f, "exy"), (V{0.3, 0.6}));
  EXPECT_EQ(scalar_field(f, "ux"), (V{3, -1}));
  EXPECT_EQ(scalar_field(f, "uy"), (V{4, 0}));
  EXPECT_EQ(scalar_field(f, "|u|"), (V{5, 1}));
  EXPECT_EQ(scalar_field(f, "vz"), (V{2, 1}));
  EXPECT_DOUBLE_EQ(scalar_field(f, "|v|")[1], std::sqrt(3.0));
  EXPECT_EQ(scalar_field(f, "material"), (V{0, 1}));
  EXPECT_EQ(scalar_field(f, "stress:3"), (V{3, 0.5}));
  EXPECT_EQ(scalar_field(f, "|displacement|"), (V{5, 1}));
  // Derived from stress when there is no array of that name (2D: in-plane).
  const double vm0 = std::sqrt(0.5 * (1 + 4 + 1) + 3 * 9.0);
  EXPECT_DOUBLE_EQ(scalar_field(f, "von_mises")[0], vm0);
  EXPECT_DOUBLE_EQ(scalar_field(f, "principal_stress_difference")[0], std::sqrt(1.0 + 36.0));
  EXPECT_EQ(scalar_field(f, "s1-s2"), scalar_field(f, "principal_stress_difference"));
  f.arrays["von_mises"] = PointArray{1, {7, 8}};
  f.arrays["damage"] = PointArray{1, {0.25, 1}};
  EXPECT_EQ(scalar_field(f, "von_mises"), (V{7, 8}));
  EXPECT_EQ(scalar_field(f, "damage"), (V{0.25, 1}));
  // 3D: principal stress difference from the eigenvalues.
  ParticleFrame g;
  g.dim = 3;
  g.x = {{0, 0, 1}};
  g.arrays["stress"] = PointArray{6, {3, -1, 2, 0, 0, 0}};
  EXPECT_NEAR(scalar_field(g, "s1-s2")[0], 4.0, 1e-12);

  f.arrays.erase("damage");
  const std::string msg = error_of([&] { scalar_field(f, "damage"); });
  EXPECT_NE(msg.find("\"damage\""), std::string::npos) << msg;
  EXPECT_NE(msg.find("offers"), std::string::npos) << msg;
  EXPECT_NE(msg.find("sxx"), std::string::npos) << msg;
  EXPECT_NE(msg.find("|u|"), std::string::npos) << msg;
  EXPECT_NE(msg.find("material"), std::string::npos) << msg;
  EXPECT_THROW(scalar_field(f, "damage"), std::invalid_argument);
  EXPECT_THROW(scalar_field(f, "nonsense"), std::invalid_argument);
  EXPECT_THROW(scalar_field(f, "stress:6"), std::invalid_argument);
  EXPECT_THROW(scalar_field(f, "stress:x"), std::invalid_argument);
  EXPECT_NE(error_of([&] { scalar_field(f, "stress"); }).find("stress:k"), std::string::npos);
  ParticleFrame bare;
  bare.x = {{0, 0, 0}};
  EXPECT_THROW(scalar_field(bare, "sxx"), std::invalid_argument);
  EXPECT_NE(error_of([&] { scalar_field(bare, "ux"); }).find("displacement"), std::string::npos);
}

TEST(CutPlane, AxisAlignedCutsOfALattice) {
  const double s = 0.25;
  const int nx = 4, ny = 5, nz = 6;
  ParticleFrame f;
  f.dim = 3;
  PointArray strain{6, {}}, id{1, {}}, size{1, {}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        f.x.push_back({(i + 0.5) * s, (j + 0.5) * s, (k + 0.5) * s});
        for (double e : {0.01, 0.02, 0.03, 0.04, 0.05, 0.06}) strain.values.push_back(e);
        id.values.push_back(i + 10 * j + 100 * k);
        size.values.push_back(s);
      }
  f.arrays["strain"] = strain;
  f.arrays["id"] = id;
  f.arrays["size"] = size;

  // Normal z through a layer's centres, and through a face between layers: one layer each (on a
  // face, the layer below: -r <= d < r).
  for (double z : {0.625, 0.5}) {
    const int layer = z == 0.625 ? 2 : 1;
    const ParticleFrame c = cut_plane(f, {0, 0, z}, {0, 0, 1});
    ASSERT_EQ(c.x.size(), static_cast<std::size_t>(nx * ny)) << z;
    EXPECT_EQ(c.dim, 2);
    for (std::size_t p = 0; p < c.x.size(); ++p) {
      const int idv = static_cast<int>(c.arrays.at("id").values[p]);
      EXPECT_EQ(idv / 100, layer) << "z = " << z;
      EXPECT_DOUBLE_EQ(c.x[p][0], (idv % 10 + 0.5) * s);
      EXPECT_DOUBLE_EQ(c.x[p][1], ((idv / 10) % 10 + 0.5) * s);
      EXPECT_EQ(c.x[p][2], 0.0);
    }
    EXPECT_EQ(c.arrays.at("strain").components, 6);
    const auto& uv = c.arrays.at("strain_uv");
    ASSERT_EQ(uv.components, 3);
    EXPECT_DOUBLE_EQ(uv.values[0], 0.01);  // xx
    EXPECT_DOUBLE_EQ(uv.values[1], 0.02);  // yy
    EXPECT_DOUBLE_EQ(uv.values[2], 0.04);  // xy
  }
  // Normal x: in-plane axes (y, z).
  {
    const ParticleFrame c = cut_plane(f, {0.375, 0, 0}, {-2, 0, 0});
    ASSERT_EQ(c.x.size(), static_cast<std::size_t>(ny * nz));
    for (std::size_t p = 0; p < c.x.size(); ++p) {
      const int idv = static_cast<int>(c.arrays.at("id").values[p]);
      EXPECT_EQ(idv % 10, 1);
      EXPECT_DOUBLE_EQ(c.x[p][0], ((idv / 10) % 10 + 0.5) * s);
      EXPECT_DOUBLE_EQ(c.x[p][1], (idv / 100 + 0.5) * s);
    }
    const auto& uv = c.arrays.at("strain_uv");
    EXPECT_DOUBLE_EQ(uv.values[0], 0.02);  // yy
    EXPECT_DOUBLE_EQ(uv.values[1], 0.03);  // zz
    EXPECT_DOUBLE_EQ(uv.values[2], 0.05);  // yz
  }
  // Normal y: in-plane axes (x, z).
  {
    const ParticleFrame c = cut_plane(f, {0, 1.2, 0}, {0, 1, 0});
    ASSERT_EQ(c.x.size(), static_cast<std::size_t>(nx * nz));
    for (std::size_t p = 0; p < c.x.size(); ++p) {
      const int idv = static_cast<int>(c.arrays.at("id").values[p]);
      EXPECT_EQ((idv / 10) % 10, 4);
      EXPECT_DOUBLE_EQ(c.x[p][0], (idv % 10 + 0.5) * s);
      EXPECT_DOUBLE_EQ(c.x[p][1], (idv / 100 + 0.5) * s);
    }
    EXPECT_DOUBLE_EQ(c.arrays.at("strain_uv").values[2], 0.06);  // xz
    // The cut rasterizes like a 2D frame and covers the whole face without holes.
    const View v = fit_view(c, 200, 300, std::nullopt, 1.0, 0.0);
    const Raster r = rasterize_2d(c, v, scalar_field(c, "id"), 1);
    for (int j = 0; j < v.height; ++j)
      for (int i = 0; i < v.width; ++i) {
        const double x = v.pixel_x(i), y = v.pixel_y(j);
        const bool inside = x > 0.01 && x < nx * s - 0.01 && y > 0.01 && y < nz * s - 0.01;
        if (inside) {
          ASSERT_TRUE(r.covered[pix(r, i, j)]) << i << "," << j;
        }
      }
  }
  // Outside the body: nothing. Without "size": the lattice spacing is used and added.
  EXPECT_TRUE(cut_plane(f, {0, 0, 10}, {0, 0, 1}).x.empty());
  ParticleFrame g = f;
  g.arrays.erase("size");
  const ParticleFrame c = cut_plane(g, {0, 0, 0.5}, {0, 0, 1});
  ASSERT_EQ(c.x.size(), static_cast<std::size_t>(nx * ny));
  EXPECT_NEAR(c.arrays.at("size").values[0], s, 1e-12);
  EXPECT_THROW(cut_plane(f, {0, 0, 0}, {0, 0, 0}), std::invalid_argument);
}

TEST(CutPlane, AxesAreOrthonormal) {
  for (std::array<double, 3> n : {std::array<double, 3>{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, 1, 0},
                                  {1, 1, 0}, {0.3, -0.2, 0.9}, {1, 2, 3}, {-1, 0.1, 0.05}}) {
    const auto [u, v] = plane_axes(n);
    const double nl = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    auto dot = [](auto a, auto b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
    EXPECT_NEAR(dot(u, u), 1.0, 1e-12);
    EXPECT_NEAR(dot(v, v), 1.0, 1e-12);
    EXPECT_NEAR(dot(u, v), 0.0, 1e-12);
    EXPECT_NEAR(dot(u, n) / nl, 0.0, 1e-12);
    EXPECT_NEAR(dot(v, n) / nl, 0.0, 1e-12);
  }
  const auto [u, v] = plane_axes({0, 1, 0});
  EXPECT_EQ(u, (std::array<double, 3>{1, 0, 0}));
  EXPECT_EQ(v, (std::array<double, 3>{0, 0, 1}));
}

TEST(Series, ReadsPvdAndFrames) {
  const fs::path dir = test_dir();
  using cleave::io::PointSet;
  cleave::io::PvdIndex pvd(dir / "particles.pvd");
  // 2D frame.
  {
    PointSet ps;
    ps.points = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    ps.arrays.push_back({"displacement", 3, {1, 2, 0, 3, 4, 0, 5, 6, 0}});
    ps.arrays.push_back({"stress", 6, std::vector<double>(18, 0.5)});
    ps.arrays.push_back({"size", 1, {0.1, 0.1, 0.1}});
    cleave::io::write_vtu(dir / "particles_000000.vtu", ps);
    pvd.add(0.0, "particles_000000.vtu");
  }
  // 3D frame.
  {
    PointSet ps;
    ps.points = {0, 0, 0, 1, 0, 0.5};
    ps.arrays.push_back({"material", 1, {2, 3}});
    cleave::io::write_vtu(dir / "particles_000001.vtu", ps);
    pvd.add(1.25e-4, "particles_000001.vtu");
  }
  pvd.write();

  for (const fs::path& where : {dir, dir / "particles.pvd"}) {
    const auto series = read_series(where);
    ASSERT_EQ(series.size(), 2u);
    EXPECT_EQ(series[0].time, 0.0);
    EXPECT_EQ(series[1].time, 1.25e-4);
    EXPECT_EQ(series[1].file, dir / "particles_000001.vtu");
  }
  const auto series = read_series(dir);
  const ParticleFrame a = read_particle_frame(series[0].file, series[0].time);
  EXPECT_EQ(a.dim, 2);
  ASSERT_EQ(a.x.size(), 3u);
  EXPECT_EQ(a.x[2], (std::array<double, 3>{0, 1, 0}));
  EXPECT_EQ(a.arrays.at("displacement").components, 3);
  EXPECT_EQ(a.arrays.at("displacement").values, (std::vector<double>{1, 2, 0, 3, 4, 0, 5, 6, 0}));
  EXPECT_EQ(a.arrays.at("stress").components, 6);
  EXPECT_EQ(a.file, series[0].file.string());
  EXPECT_EQ(scalar_field(a, "uy"), (std::vector<double>{2, 4, 6}));
  const ParticleFrame b = read_particle_frame(series[1].file, series[1].time);
  EXPECT_EQ(b.dim, 3);
  EXPECT_EQ(b.time, 1.25e-4);
  EXPECT_EQ(b.arrays.at("material").values, (std::vector<double>{2, 3}));
  // The frame goes straight through the pipeline.
  const View v = fit_view(a, 64, 64, std::nullopt, 1.0);
  const Raster r = rasterize_2d(a, v, scalar_field(a, "|u|"), 1);
  EXPECT_GT(count_covered(r), 0u);
}

TEST(Series, ErrorsNameTheFile) {
  const fs::path dir = test_dir();
  // Missing .pvd in a directory.
  std::string msg = error_of([&] { read_series(dir); });
  EXPECT_NE(msg.find((dir / "particles.pvd").string()), std::string::npos) << msg;
  EXPECT_THROW(read_series(dir), std::runtime_error);
  EXPECT_THROW(read_series(dir / "nope.pvd"), std::runtime_error);
  // Empty collection.
  cleave::io::PvdIndex(dir / "particles.pvd").write();
  msg = error_of([&] { read_series(dir); });
  EXPECT_NE(msg.find("particles.pvd"), std::string::npos) << msg;
  EXPECT_NE(msg.find("no frames"), std::string::npos) << msg;
  // Unreadable .pvd.
  {
    std::ofstream(dir / "bad.pvd") << "not xml at all";
  }
  msg = error_of([&] { read_series(dir / "bad.pvd"); });
  EXPECT_NE(msg.find("bad.pvd"), std::string::npos) << msg;
  // Frames: missing and garbage.
  msg = error_of([&] { read_particle_frame(dir / "missing.vtu", 0); });
  EXPECT_NE(msg.find("missing.vtu"), std::string::npos) << msg;
  EXPECT_THROW(read_particle_frame(dir / "missing.vtu", 0), std::runtime_error);
  {
    std::ofstream(dir / "garbage.vtu") << "garbage";
  }
  msg = error_of([&] { read_particle_frame(dir / "garbage.vtu", 0); });
  EXPECT_NE(msg.find("garbage.vtu"), std::string::npos) << msg;
  EXPECT_THROW(read_particle_frame(dir, 0), std::runtime_error);
}

// Coverage at scale; the time is printed for information only (no test asserts wall time: a loaded
// machine must not fail CI). cleave-render-bench measures it (docs/performance.md).
TEST(Rasterize, OneMillionParticlesFullHdCoverTheImage) {
  const int N = 1000;
  const double s = 1e-3;
  ParticleFrame f;
  f.x.reserve(static_cast<std::size_t>(N) * N);
  std::vector<double> val;
  val.reserve(static_cast<std::size_t>(N) * N);
  PointArray size{1, {}}, strain{6, {}};
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i) {
      const double x = (i + 0.5) * s, y = (j + 0.5) * s;
      f.x.push_back({x, y, 0});
      size.values.push_back(s);
      for (double e : {1e-3, -5e-4, 0.0, 2e-4, 0.0, 0.0}) strain.values.push_back(e);
      val.push_back(x * x - y);
    }
  f.arrays["size"] = std::move(size);
  f.arrays["strain"] = std::move(strain);
  const View v = fit_view(f, 1920, 1080, std::nullopt, 1.0);
  auto time_it = [&] {
    double best = 1e30;
    std::size_t covered = 0;
    for (int rep = 0; rep < 3; ++rep) {
      const auto t0 = std::chrono::steady_clock::now();
      const Raster r = rasterize_2d(f, v, val, 1);
      const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      best = std::min(best, dt);
      covered = count_covered(r);
    }
    EXPECT_GT(covered, 1000000u);
    return best;
  };
#ifdef _OPENMP
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const double one = time_it();
  omp_set_num_threads(saved);
  const double all = time_it();
  std::printf("[ timing   ] rasterize_2d 1e6 particles -> 1920x1080: %.3f s on 1 thread, %.3f s on %d threads\n",
              one, all, saved);
#else
  const double one = time_it();
  std::printf("[ timing   ] rasterize_2d 1e6 particles -> 1920x1080: %.3f s (no OpenMP)\n", one);
#endif
}
