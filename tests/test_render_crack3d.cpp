// Rendering 3D cracks: the faces with their opening scaled, the traces of a crack in a section (drawn
// and as smoothing barriers), frozen-stress slices, and the options of `cleave render` for them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "libmpm/io/pvd_writer.hpp"
#include "libmpm/io/vtu_writer.hpp"
#include "viz/job/crack_frames.hpp"
#include "viz/optics/photoelastic.hpp"
#include "viz/raster/crack_section.hpp"
#include "viz/raster/rasterize.hpp"
#include "viz/raster/slice.hpp"
#include "viz/raster/smooth.hpp"
#include "viz/render/headless.hpp"

namespace cleave::viz {
namespace {

namespace fs = std::filesystem;

// A penny crack of radius R centred at c in the plane z = c.z: a centre point and `rings` rings of
// `sectors` points, each point's faces at +-h(r) along z with h = open/2 sqrt(1 - r^2/R^2), the
// elliptical opening of a penny crack under tension (zero at the front).
CrackSurfaces penny(const Point3& c, double R, double open, int rings = 8, int sectors = 24) {
  CrackSurfaces s;
  auto add = [&](double r, double a) {
    const double h = 0.5 * open * std::sqrt(std::max(0.0, 1 - r * r / (R * R)));
    const Point3 p{c[0] + r * std::cos(a), c[1] + r * std::sin(a), c[2]};
    s.above.push_back({p[0], p[1], p[2] + h});
    s.below.push_back({p[0], p[1], p[2] - h});
  };
  add(0, 0);
  for (int k = 1; k <= rings; ++k)
    for (int j = 0; j < sectors; ++j) add(R * k / rings, 2 * std::numbers::pi * j / sectors);
  auto id = [&](int k, int j) { return std::size_t(1 + (k - 1) * sectors + (j % sectors)); };
  for (int j = 0; j < sectors; ++j) {
    s.triangles.push_back({0, id(1, j), id(1, j + 1)});
    for (int k = 1; k < rings; ++k) {
      s.triangles.push_back({id(k, j), id(k + 1, j), id(k + 1, j + 1)});
      s.triangles.push_back({id(k, j), id(k + 1, j + 1), id(k, j + 1)});
    }
  }
  return s;
}

// A lattice of nx x ny x nz particles of edge s, centres at ((i + 1/2) s, (j + 1/2) s, (k + 1/2) s),
// with the stress stress(x) (six components, VTK order).
template <class F>
ParticleFrame lattice(int nx, int ny, int nz, double s, F stress) {
  ParticleFrame f;
  f.dim = 3;
  PointArray st{6, {}}, size{1, {}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const Point3 x{(i + 0.5) * s, (j + 0.5) * s, (k + 0.5) * s};
        f.x.push_back(x);
        const std::array<double, 6> t = stress(x);
        st.values.insert(st.values.end(), t.begin(), t.end());
        size.values.push_back(s);
      }
  f.arrays["stress"] = st;
  f.arrays["size"] = size;
  return f;
}

PhotoelasticSettings photo(double thickness) {
  PhotoelasticSettings p;
  p.thickness = thickness;
  p.fringe_constant = 7e3;  // 7 N/mm/fringe
  return p;
}

TEST(CrackFaces3D, TheOpeningScaleMovesEachFaceKTimesItsDistanceFromTheMidSurface) {
  const Point3 above{1.0, 2.0, 3.5}, below{1.2, 2.0, 2.5}, mid{1.1, 2.0, 3.0};
  for (double K : {1.0, 0.5, 50.0})
    for (CrackFace face : {CrackFace::Above, CrackFace::Below}) {
      const Point3& x = face == CrackFace::Above ? above : below;
      const Point3 p = opened_face_point(above, below, K, face);
      for (std::size_t d = 0; d < 3; ++d) EXPECT_NEAR(p[d] - mid[d], K * (x[d] - mid[d]), 1e-12) << "K " << K;
    }
  EXPECT_EQ(opened_face_point(above, below, 1.0, CrackFace::Above), above);
  EXPECT_EQ(opened_face_point(above, below, 1.0, CrackFace::Below), below);

  // Over a whole crack: the gap between the drawn faces is K times the opening, point by point; an
  // unopened crack stays where it is at any K.
  const CrackSurfaces s = penny({0, 0, 0}, 1.0, 0.02);
  const auto a = opened_face_points(s, 40, CrackFace::Above), b = opened_face_points(s, 40, CrackFace::Below);
  ASSERT_EQ(a.size(), s.above.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i][2] - b[i][2], 40 * (s.above[i][2] - s.below[i][2]), 1e-12);
  EXPECT_NEAR(max_opening(s), 0.02, 1e-15);
  const CrackSurfaces shut = penny({0, 0, 0}, 1.0, 0.0);
  EXPECT_EQ(opened_face_points(shut, 40, CrackFace::Above), shut.above);
  EXPECT_EQ(max_opening(shut), 0.0);
}

TEST(CrackFaces3D, AnUnopenedCrackAtScaleOneIsDrawnRedAsBeforeItsFacesWereDrawnApart) {
  HeadlessContext ctx(160, 120);
  const CrackSurfaces shut = penny({0, 0, 0}, 0.4, 0.0);
  ColorBar none;
  none.show = false;
  for (double K : {1.0, 30.0}) {
    const Image im = render_particles_3d(ctx, {{0, 0, 0}}, {1.0}, {{128, 128, 128}}, Camera3D{}, "", "", none, {1, 1, 1},
                                         crack_faces_3d(shut, K));
    std::size_t red = 0, blue = 0;
    for (std::size_t i = 0; i < im.rgb.size(); i += 3) {
      red += im.rgb[i] > 2 * im.rgb[i + 2] + 40;
      blue += im.rgb[i + 2] > 2 * im.rgb[i] + 40;
    }
    EXPECT_GT(red, 300u) << "K " << K;
    EXPECT_EQ(blue, 0u) << "K " << K << ": the face below shows through the coincident face above";
  }
}

TEST(CrackSection, APlaneThroughAPennyCrackCutsItsFacesAlongADiameterAndAPlaneBesideItCutsNothing) {
  const Point3 c{0.010, 0.010, 0.0055};
  const double R = 0.005, open = 1e-4;
  const CrackSurfaces s = penny(c, R, open);
  for (double K : {1.0, 10.0}) {
    for (CrackFace face : {CrackFace::Above, CrackFace::Below}) {
      const auto lines = face_section(s, K, face, c, {0, 1, 0});  // section axes (x, z)
      ASSERT_EQ(lines.size(), 1u) << "one joined trace per face";
      const auto& l = lines[0];
      double umin = 1, umax = -1, wmid = 0;
      for (const auto& p : l) {
        umin = std::min(umin, p[0]), umax = std::max(umax, p[0]);
        // On the face drawn: between the mid-surface and the elliptical profile (a chord of it).
        const double r = std::abs(p[0] - c[0]);
        const double h = 0.5 * K * open * std::sqrt(std::max(0.0, 1 - r * r / (R * R)));
        const double off = face == CrackFace::Above ? p[1] - c[2] : c[2] - p[1];
        EXPECT_GE(off, -1e-15);
        EXPECT_LE(off, h + 1e-15);
        if (std::abs(p[0] - c[0]) < 1e-12) wmid = p[1];
      }
      EXPECT_NEAR(umin, c[0] - R, 1e-12);
      EXPECT_NEAR(umax, c[0] + R, 1e-12);
      EXPECT_NEAR(wmid, c[2] + (face == CrackFace::Above ? 0.5 : -0.5) * K * open, 1e-15) << "the opening at the centre, x K";
    }
    // Off the centre the trace is the chord of the circle at that distance.
    const auto off = face_section(s, K, CrackFace::Above, {c[0], c[1] + 0.6 * R, c[2]}, {0, 1, 0});
    ASSERT_EQ(off.size(), 1u);
    double umin = 1, umax = -1;
    for (const auto& p : off[0]) umin = std::min(umin, p[0]), umax = std::max(umax, p[0]);
    EXPECT_NEAR(umax - umin, 2 * 0.8 * R, 0.03 * R);  // the polygon's chord, within its sagitta
    EXPECT_TRUE(face_section(s, K, CrackFace::Above, {c[0], c[1] + 1.2 * R, c[2]}, {0, 1, 0}).empty());
    EXPECT_TRUE(face_section(s, K, CrackFace::Below, {c[0], c[1] - 1.2 * R, c[2]}, {0, -1, 0}).empty());
  }
  // The smoothing barriers are both traces where they are.
  const auto bars = section_barriers(s, c, {0, 1, 0});
  ASSERT_FALSE(bars.empty());
  for (const auto& b : bars) {
    EXPECT_LE(std::abs(b[1] - c[2]), 0.5 * open + 1e-15);
    EXPECT_LE(std::abs(b[3] - c[2]), 0.5 * open + 1e-15);
  }
}

TEST(CrackSection, TheSmoothingOfASectionDoesNotAverageAcrossTheCrackTrace) {
  // szz jumps from -1 to +1 across z = 4 s everywhere; a penny crack of radius 9 s lies there.
  const double s = 1e-3;
  const ParticleFrame f = lattice(24, 4, 8, s, [&](const Point3& x) {
    const double v = x[2] > 4 * s ? 1.0 : -1.0;
    return std::array<double, 6>{0, 0, v, 0, 0, 0};
  });
  const Point3 c{12 * s, 2 * s, 4 * s};
  const ParticleFrame sec = cut_plane(f, c, {0, 1, 0});
  SmoothSettings with;
  with.barriers = section_barriers(penny(c, 9 * s, 0.0), c, {0, 1, 0});
  const ParticleFrame a = smooth_stress(sec, with), b = smooth_stress(sec, SmoothSettings{});
  std::size_t near_crack = 0;
  for (std::size_t p = 0; p < sec.x.size(); ++p) {
    const double u = sec.x[p][0], w = sec.x[p][1];
    // Beside the crack, farther from its tips than the smoothing reaches (3 x 1.5 spacings).
    if (std::abs(u - c[0]) > 4 * s || std::abs(w - c[2]) > 0.6 * s) continue;
    ++near_crack;
    const double expect = w > c[2] ? 1.0 : -1.0;
    EXPECT_NEAR(a.arrays.at("stress_uv").values[3 * p + 1], expect, 1e-12) << "at u " << u << ", w " << w;
    EXPECT_GT(std::abs(b.arrays.at("stress_uv").values[3 * p + 1] - expect), 0.05) << "without barriers it blurs";
  }
  EXPECT_EQ(near_crack, 16u);  // two layers of eight particles
}

TEST(FrozenStressSlice, ASlabOfUniformStressGivesTheFringeOrderOfAOneLayerSectionOfTheSameThickness) {
  const double s = 1e-3, t = 4 * s;
  const std::array<double, 6> sigma{3e6, -1e6, 5e6, 0.5e6, 0.7e6, 1.2e6};
  const ParticleFrame f = lattice(8, 8, 8, s, [&](const Point3&) { return sigma; });
  for (double y : {4 * s, 4.5 * s, 4.3 * s}) {  // on a lattice face, through a layer, anywhere
    const ParticleFrame sec = cut_plane(f, {0, y, 0}, {0, 1, 0});
    const ParticleFrame sl = slice_plane(f, {0, y, 0}, {0, 1, 0}, t);
    ASSERT_EQ(sec.x.size(), 64u);
    ASSERT_EQ(sl.x.size(), 64u) << "one column per in-plane lattice position";
    EXPECT_EQ(sl.dim, 2);
    const auto& a = sec.arrays.at("stress_uv").values;
    const auto& b = sl.arrays.at("stress_uv").values;
    const double n_section = fringe_order(a[0], a[1], a[2], photo(t));
    EXPECT_NEAR(n_section, t * std::hypot(sigma[0] - sigma[2], 2 * sigma[5]) / 7e3, 1e-9);
    for (std::size_t p = 0; p < sl.x.size(); ++p) {
      EXPECT_NEAR(fringe_order(b[3 * p], b[3 * p + 1], b[3 * p + 2], photo(t)), n_section, 1e-9 * n_section);
      const double u = sl.x[p][0] / s - 0.5, w = sl.x[p][1] / s - 0.5;  // on the lattice columns
      EXPECT_NEAR(u, std::round(u), 1e-9);
      EXPECT_NEAR(w, std::round(w), 1e-9);
    }
  }
  // Half the slab outside the body: only the material retards.
  const ParticleFrame edge = slice_plane(f, {0, 0, 0}, {0, 1, 0}, t);
  ASSERT_EQ(edge.x.size(), 64u);
  const auto& e = edge.arrays.at("stress_uv").values;
  EXPECT_NEAR(fringe_order(e[0], e[1], e[2], photo(t)), 0.5 * t * std::hypot(sigma[0] - sigma[2], 2 * sigma[5]) / 7e3,
              1e-9);
  EXPECT_TRUE(slice_plane(f, {0, 0.1, 0}, {0, 1, 0}, t).x.empty());
  EXPECT_THROW(slice_plane(f, {0, 0, 0}, {0, 1, 0}, 0.0), std::invalid_argument);
  EXPECT_THROW(slice_plane(f, {0, 0, 0}, {0, 0, 0}, t), std::invalid_argument);
}

TEST(FrozenStressSlice, ASlabOfStressLinearThroughItsThicknessGivesTheMidPlaneFringeOrder) {
  const double s = 1e-3, t = 4 * s;
  const std::array<double, 6> mid{3e6, -1e6, 5e6, 0.5e6, 0.7e6, 1.2e6}, grad{2e9, 0, -3e9, 1e9, 0, 1.5e9};  // Pa/m along y
  for (double y0 : {4 * s, 4.5 * s}) {  // the slab centred between two layers, and on one
    const ParticleFrame f = lattice(6, 9, 6, s, [&](const Point3& x) {
      std::array<double, 6> r;
      for (std::size_t k = 0; k < 6; ++k) r[k] = mid[k] + grad[k] * (x[1] - y0);
      return r;
    });
    const ParticleFrame sl = slice_plane(f, {0, y0, 0}, {0, 1, 0}, t);
    ASSERT_EQ(sl.x.size(), 36u);
    const double n_mid = fringe_order(mid[0], mid[2], mid[5], photo(t));
    const double n_face = fringe_order(mid[0] + grad[0] * t / 2, mid[2] + grad[2] * t / 2, mid[5] + grad[5] * t / 2, photo(t));
    ASSERT_GT(std::abs(n_face - n_mid), 0.5) << "the stress varies enough to tell";
    const auto& b = sl.arrays.at("stress_uv").values;
    for (std::size_t p = 0; p < sl.x.size(); ++p)
      EXPECT_NEAR(fringe_order(b[3 * p], b[3 * p + 1], b[3 * p + 2], photo(t)), n_mid, 1e-9 * n_mid) << "y0 " << y0;
  }
}

// `cleave render` on a small synthetic 3D series with a penny crack.
class RenderCrack3DCli : public test::CliTest {
 protected:
  RenderCrack3DCli() : CliTest("render_crack3d_") {}
  void SetUp() override {
    CliTest::SetUp();
    const double s = 1e-3;
    const ParticleFrame f = lattice(20, 20, 10, s, [&](const Point3& x) {
      const double r = std::hypot(x[0] - 0.01, x[1] - 0.01);
      return std::array<double, 6>{1e6 * r / 0.01, 0, 8e6 * std::exp(-r / 0.003), 0, 0, 2e6 * (x[2] - 0.005) / 0.005};
    });
    fs::create_directories(dir_ / "out");
    io::PointSet ps;
    for (const auto& x : f.x) ps.points.insert(ps.points.end(), x.begin(), x.end());
    ps.arrays = {{"stress", 6, f.arrays.at("stress").values}, {"size", 1, f.arrays.at("size").values}};
    io::write_vtu(dir_ / "out" / "particles_000000.vtu", ps);
    io::PvdIndex pvd(dir_ / "out" / "particles.pvd");
    pvd.add(0.0, "particles_000000.vtu");
    pvd.write();
    const CrackSurfaces c = penny({0.0103, 0.0103, 0.005}, 0.005, 1e-4);  // between particle layers
    io::PointSet cs;
    io::PointArray above{"above", 3, {}}, below{"below", 3, {}};
    for (std::size_t i = 0; i < c.above.size(); ++i) {
      const Point3 m = opened_face_point(c.above[i], c.below[i], 0.0, CrackFace::Above);  // K = 0: the mid-surface
      cs.points.insert(cs.points.end(), m.begin(), m.end());
      above.values.insert(above.values.end(), c.above[i].begin(), c.above[i].end());
      below.values.insert(below.values.end(), c.below[i].begin(), c.below[i].end());
    }
    cs.arrays = {above, below};
    for (const auto& t : c.triangles) cs.triangles.push_back({int64_t(t[0]), int64_t(t[1]), int64_t(t[2])});
    io::write_vtu(dir_ / "out" / "cracks_000000.vtu", cs);
    io::PvdIndex cp(dir_ / "out" / "cracks.pvd");
    cp.add(0.0, "cracks_000000.vtu");
    cp.write();
  }
  test::Result render(const std::string& opts) {
    return test::run_headless("render " + (dir_ / "out").string() + " --frames last --size 320x240 --images " +
                                  (dir_ / "img").string() + " " + opts,
                              dir_);
  }
  // Pixels of the one image rendered that are clearly red and clearly blue.
  std::array<std::size_t, 2> red_and_blue(const std::string& name) {
    const Image im = read_image(dir_ / "img" / name);
    std::array<std::size_t, 2> n{0, 0};
    for (std::size_t i = 0; i < im.rgb.size(); i += 3) {  // shaded faces are darker: hue, not brightness
      const int r = im.rgb[i], g = im.rgb[i + 1], b = im.rgb[i + 2];
      n[0] += r > 60 && r > 2.5 * g && r > 2.5 * b;
      n[1] += b > 60 && b > 2.5 * r && b > 1.5 * g;
    }
    return n;
  }
};

TEST_F(RenderCrack3DCli, DrawsBothFacesOverTheCubesAndTheirTracesInASectionAndASlice) {
  auto r = render("--opening-scale 30 --camera xz --field von_mises --colormap gray");
  ASSERT_EQ(r.code, 0) << r.err;
  auto rb = red_and_blue("von_mises_000000.png");
  EXPECT_GT(rb[0], 200u);
  EXPECT_GT(rb[1], 200u) << "the face below, opened 30 times, shows beneath the face above";
  std::printf("xz view: %zu red, %zu blue\n", rb[0], rb[1]);
  for (const std::string slice : {"", " --slice 4"}) {
    fs::remove_all(dir_ / "img");
    r = render("--length-unit mm --cut-plane 10.3,10.3,5,0,1,0 --fringes dark --fringe-constant 7 --opening-scale 30" +
               slice);
    ASSERT_EQ(r.code, 0) << slice << ": " << r.err;
    rb = red_and_blue("fringes_000000.png");
    EXPECT_GT(rb[0], 50u) << slice << ": the trace of the face above";
    EXPECT_GT(rb[1], 50u) << slice << ": the trace of the face below";
    std::printf("section%s: %zu red, %zu blue\n", slice.c_str(), rb[0], rb[1]);
  }
}

TEST_F(RenderCrack3DCli, BadSliceAndOpeningScaleOptionsExitWithStatus2NamingTheOption) {
  const std::string cut = "--length-unit mm --cut-plane 10,10,5,0,1,0 --fringes dark --fringe-constant 7 ";
  for (const auto& [opts, says] : std::vector<std::pair<std::string, std::string>>{
           {"--slice 4 --fringes dark --fringe-constant 7", "--cut-plane"},
           {cut + "--slice 0", "--slice"},
           {cut + "--slice -2", "--slice"},
           {cut + "--slice nan", "--slice"},
           {cut + "--slice 4 --thickness 2", "--thickness"},
           {"--opening-scale 0", "--opening-scale"},
           {"--opening-scale -1", "--opening-scale"},
           {"--opening-scale nan", "--opening-scale"},
           {"--opening-scale", "--opening-scale"}}) {
    const auto r = render(opts);
    EXPECT_EQ(r.code, 2) << opts << "\n" << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << opts << "\n" << r.err;
  }
  // A 2D series has no slab to slice.
  io::PointSet ps;
  ps.points = {0, 0, 0, 1e-3, 0, 0, 0, 1e-3, 0};
  ps.arrays = {{"stress", 6, std::vector<double>(18, 1e6)}};
  fs::create_directories(dir_ / "flat");
  io::write_vtu(dir_ / "flat" / "particles_000000.vtu", ps);
  io::PvdIndex pvd(dir_ / "flat" / "particles.pvd");
  pvd.add(0.0, "particles_000000.vtu");
  pvd.write();
  const auto r = test::run_headless("render " + (dir_ / "flat").string() + " " + cut + "--slice 1", dir_);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("--slice needs a 3D series"), std::string::npos) << r.err;
}

TEST_F(RenderCrack3DCli, PlotCodOfA3DRunSaysItIsFor2DCracksAndNamesWhatDrawsA3DOpening) {
  const auto r = test::run_headless("plot " + (dir_ / "out").string() + " --cod 0", dir_);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("--cod plots the opening along 2D cracks"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--opening-scale"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace cleave::viz
