// 3D explicit cracks (seed 000, CRAMP in 3D; issue 16 validations 1-3): the crack patch test, the
// agreement of a through-cracked slab with the 2D plane-strain DCB, and rigid motion of a body with
// an embedded penny crack. Figures: docs/validation.md, "3D cracks".
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/LU>
#include <map>
#include <tuple>

#include "libmpm/crack/fronts.hpp"
#include "support.hpp"

namespace cleave {
namespace {

using test::json;

// Validation 1, the 3D crack patch test: a block with an edge crack on the mid-plane z = 0 (a node
// plane), its arms pulled apart by shear tractions on the cracked face, against its top half with a
// symmetry condition (w = 0) on the ligament's nodes. The tip edge x = 10 mm lies half-way between
// node planes; the crack, given wider than the body, is clipped to it. Contact "none", linear shape
// functions, as in the 2D patch test (test_crack_validation.cpp says why).
json patch_scene(bool half) {
  json s;
  s["units"] = {{"length", "mm"}, {"stress", "Pa"}, {"density", "g/cm3"}, {"time", "s"}};
  s["analysis"] = {{"type", "3d"}};
  s["grid"] = {{"min", {-2.5, -2, -6}}, {"max", {22.5, 12, 6}}, {"cell_size", 1}};
  s["mpm"] = {{"shape_function", "linear"}, {"stress_update", "USAVG"}};
  s["materials"] = json::array({test::material("soft", 1e5, 0.33, 1.5)});
  s["bodies"] = json::array({{{"name", "b"}, {"material", "soft"},
                              {"shape", {{"type", "box"}, {"min", {0, 0, half ? 0 : -5}}, {"max", {20, 10, 5}}}}}});
  json loads = json::array({{{"type", "traction"}, {"face", "-x"}, {"region", {{"min", {-1, -1, 0}}, {"max", {1, 11, 5}}}},
                             {"traction", {0, 0, 20}}, {"rise_time", 0.02}}});
  if (half) {
    loads.push_back({{"type", "velocity"}, {"region", {{"min", {10.4, -3, -0.01}}, {"max", {23, 13, 0.01}}}},
                     {"velocity", {nullptr, nullptr, 0}}});
  } else {
    loads.push_back({{"type", "traction"}, {"face", "-x"}, {"region", {{"min", {-1, -1, -5}}, {"max", {1, 11, 0}}}},
                     {"traction", {0, 0, -20}}, {"rise_time", 0.02}});
    s["cracks"] = json::array({{{"name", "edge"},
                                {"rectangle", {{"corner", {-1, -1, 0}}, {"edges", {{11, 0, 0}, {0, 12, 0}}}}},
                                {"contact", {{"law", "none"}}}}});
  }
  s["loads"] = loads;
  s["time"] = {{"end", 0.03}, {"cfl", 0.5}};
  return s;
}


TEST(Crack3dPatch, TopHalfOfACrackedBlockEqualsTheHalfModelWithASymmetryPlane) {
  Model<3> mf = build_model<3>(patch_scene(false)), mh = build_model<3>(patch_scene(true));
  ASSERT_EQ(mf.particles.size(), 2 * mh.particles.size());
  ASSERT_EQ(mf.dt, mh.dt);
  ASSERT_EQ(mf.cracks.size(), 1u);
  ASSERT_EQ(mf.cracks[0].fronts.size(), 1u);  // the tip edge; the edges on the faces are mouths
  const std::vector<std::size_t> twin = test::twins(mf.particles, mh.particles);
  ASSERT_EQ(twin.size(), mh.particles.size());  // every particle of the half model has its twin
  auto sf = make_stepper<3>(mf), sh = make_stepper<3>(mh);
  test::TwinDifference<3> d;
  double umax = 0;
  const long steps = std::lround(mf.end_time / mf.dt);
  for (long k = 0; k < steps; ++k) {
    ASSERT_FALSE(sf->step());
    ASSERT_FALSE(sh->step());
    if (k % 50 != 49 && k != steps - 1) continue;
    d.add(mf.particles, mh.particles, twin, 0.02);  // relative to the block's length, 20 mm
    for (std::size_t p = 0; p < mh.particles.size(); ++p) umax = std::max(umax, mh.particles.u[p].norm());
  }
  const double worst_x = d.x, worst_s = d.stress;
  EXPECT_GT(umax, 1e-5);  // the arms did open (tens of um)
  EXPECT_LT(worst_x, 1e-10);
  EXPECT_LT(worst_s, 1e-10);
  std::printf("3D crack patch test over %ld steps: max |u| %.3g m, max relative difference %.2e (positions), %.2e "
              "(stresses)\n", steps, umax, worst_x, worst_s);
}

// Validation 2: the DCB of data/scenes/dcb_crack.json in plane strain, in 2D and as a 3D slab one
// cell thick between two symmetry planes, its crack a rectangle through the slab (clipped to it):
// the load-point openings agree within 0.5 % (issue 16). Contact as the scene has it (frictionless,
// displacement detection: the faces separate, so it never acts).
TEST(Crack3dSlab, ThroughCrackedSlabOpensAsThePlaneStrainDcb) {
  const double end = 0.1;
  Model<2> m2 = build_model<2>(test::dcb_slab_scene(2, end));
  Model<3> m3 = build_model<3>(test::dcb_slab_scene(3, end));
  ASSERT_EQ(m3.particles.size(), 2 * m2.particles.size());
  ASSERT_DOUBLE_EQ(m2.dt, m3.dt);
  auto s2 = make_stepper<2>(m2);
  auto s3 = make_stepper<3>(m3);
  const long steps = std::lround(end / m2.dt);
  ASSERT_FALSE(test::advance(*s2, steps));
  ASSERT_FALSE(test::advance(*s3, steps));
  const double o2 = test::dcb_load_point_opening(m2.particles), o3 = test::dcb_load_point_opening(m3.particles);
  std::printf("DCB load-point opening at %.3g s: 2D plane strain %.6e m, 3D slab %.6e m (%.3e relative)\n", end, o2, o3,
              o3 / o2 - 1);
  ASSERT_GT(o2, 1e-4);
  EXPECT_NEAR(o3 / o2, 1.0, 5e-3);
}

constexpr double h = 1e-3;  // the rigid-motion tests' cell (m)

// A 10 mm aluminium block in 1 mm cells, moving at `velocity`, with a penny crack (radius 3 mm, normal
// `normal`, frictionless contact) inside it, run to `end` at CFL 0.5.
json moving_penny_block(const json& grid_min, const json& grid_max, const json& velocity, const json& normal,
                        double end) {
  json s;
  s["analysis"] = {{"type", "3d"}};
  s["grid"] = {{"min", grid_min}, {"max", grid_max}, {"cell_size", h}};
  s["mpm"] = {{"shape_function", "linear"}, {"stress_update", "USAVG"}};
  s["materials"] = json::array({test::material("al", 70e9, 0.33, 2700)});
  s["bodies"] = json::array({{{"name", "b"}, {"material", "al"},
                              {"shape", {{"type", "box"}, {"min", {0, 0, 0}}, {"max", {0.01, 0.01, 0.01}}}},
                              {"velocity", velocity}}});
  s["cracks"] = json::array({{{"name", "penny"},
                              {"ellipse", {{"center", {0.0051, 0.0049, 0.0055}}, {"normal", normal}, {"radius", 0.003}}},
                              {"contact", {{"law", "frictionless"}}}}});
  s["time"] = {{"end", end}, {"cfl", 0.5}};
  return s;
}

// Validation 3: a block with an embedded penny crack moving rigidly: the crack points follow the body
// (drift below 1e-6 of a cell from the rigid position), the faces do not open, energy stays constant.
TEST(Crack3dMotion, PennyCrackInATranslatingBlockFollowsItWithoutOpening) {
  const Vec<3> v(500.0, 200.0, -100.0);  // m/s
  const double end = 6e-6;               // 3 mm of travel along x: three cells
  Model<3> m = build_model<3>(
      moving_penny_block({-0.004, -0.003, -0.003}, {0.021, 0.013, 0.013}, {v.x(), v.y(), v.z()}, {0, 0, 1}, end));
  const std::vector<Vec<3>> start = m.cracks[0].points;
  auto st = make_stepper<3>(m);
  const auto e0 = st->global_state();
  const long steps = std::lround(end / m.dt);
  ASSERT_FALSE(test::advance(*st, steps));
  const auto e1 = st->global_state();
  const double t = st->time();
  double drift = 0, opening = 0;
  const auto& c = m.cracks[0];
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    drift = std::max(drift, (c.points[i] - (start[i] + t * v)).norm());
    opening = std::max(opening, (c.above[i] - c.below[i]).norm());
  }
  std::printf("penny crack translated %.3g cells in %ld steps: drift %.2e cell, opening %.2e cell, energy %.2e\n",
              t * v.x() / h, steps, drift / h, opening / h, std::abs(e1.total() / e0.total() - 1));
  EXPECT_LT(drift / h, 1e-6);
  EXPECT_LT(opening / h, 1e-6);
  EXPECT_NEAR(e1.total() / e0.total(), 1.0, 1e-3);
}

// Validation 3, rotation: the same block turning slowly about a skew axis while translating. The
// velocity field is linear, which the grid interpolates exactly, so every material point (particle
// or crack point) moves by one affine map per step: the crack points must stay where the map fitted
// to the particles takes their start (to 1e-6 of a cell), with no opening and constant energy.
TEST(Crack3dMotion, PennyCrackInASlowlyRotatingBlockFollowsItWithoutOpening) {
  const double kW[3] = {3, -2, 5};  // rad/s: 6e-5 rad over the run
  const double end = 1e-5;
  json s = moving_penny_block({-0.004, -0.004, -0.004}, {0.016, 0.016, 0.016}, {100, -50, 30}, {0.2, 0.1, 1}, end);
  s["bodies"][0]["angular_velocity"] = {kW[0], kW[1], kW[2]};
  Model<3> m = build_model<3>(s);
  const auto& P = m.particles;
  const std::vector<Vec<3>> X = P.x, start = m.cracks[0].points;
  auto st = make_stepper<3>(m);
  const auto e0 = st->global_state();
  const long steps = std::lround(end / m.dt);
  ASSERT_FALSE(test::advance(*st, steps));
  const auto e1 = st->global_state();
  // The affine map x = A X + b fitted to the particles (least squares, about the centroid).
  Vec<3> Xm = Vec<3>::Zero(), xm = Vec<3>::Zero();
  for (std::size_t p = 0; p < P.size(); ++p) Xm += X[p], xm += P.x[p];
  Xm /= double(P.size()), xm /= double(P.size());
  Mat<3> XX = Mat<3>::Zero(), xX = Mat<3>::Zero();
  for (std::size_t p = 0; p < P.size(); ++p) {
    XX += (X[p] - Xm) * (X[p] - Xm).transpose();
    xX += (P.x[p] - xm) * (X[p] - Xm).transpose();
  }
  const Mat<3> A = xX * XX.inverse();
  double drift = 0, opening = 0, turned = 0;
  const auto& c = m.cracks[0];
  // The body's own departure from the affine map near the crack. Before mpm.spin_transfer (on here: the
  // body has an angular velocity) the free faces' nodes carried the velocity of their particles' mass
  // centre, and a turning body gained a spurious strain there (about 0.012 cell of displacement per
  // radian turned), which this test used as the yardstick of the opening; now the material keeps to
  // the map to round-off (1.6e-10 cell) and the opening is held to the 1e-6 cell, as in the
  // translating block (it reads 3.3e-10 cell).
  double material = 0;
  for (std::size_t p = 0; p < P.size(); ++p)
    if ((X[p] - Vec<3>(0.0051, 0.0049, 0.0055)).norm() < 0.004)
      material = std::max(material, (P.x[p] - (xm + A * (X[p] - Xm))).norm());
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    drift = std::max(drift, (c.points[i] - (xm + A * (start[i] - Xm))).norm());
    opening = std::max(opening, (c.above[i] - c.below[i]).norm());
    turned = std::max(turned, (c.points[i] - start[i]).norm());
  }
  std::printf("penny crack turned by %.3g rad (%.3g cells of travel) in %ld steps: drift %.2e cell, opening %.2e "
              "cell (particles near it: %.2e cell off the map), energy %.2e\n",
              std::sqrt(kW[0] * kW[0] + kW[1] * kW[1] + kW[2] * kW[2]) * st->time(), turned / h, steps, drift / h,
              opening / h, material / h, std::abs(e1.total() / e0.total() - 1));
  EXPECT_GT(turned / h, 0.5);
  EXPECT_LT(drift / h, 1e-6);
  EXPECT_LE(drift, material);  // the crack follows the map at least as closely as the material beside it
  EXPECT_LT(opening / h, 1e-6);
  EXPECT_NEAR(e1.total() / e0.total(), 1.0, 1e-3);
}

// Validation 4: two blocks, each with a penny crack normal to the impact, driven into each other:
// the compression closes the cracks, the reflected tension opens them. For each contact law and
// detection: momentum conserved to 1e-10 (relative to sum m |v|), the tracked faces never cross by
// more than 1 % of a cell.
using LawDetection = std::pair<std::string, std::string>;
class CollidingCrackedBlocks : public ::testing::TestWithParam<LawDetection> {};

// uGIMP and a crack whose corner lies on two symmetry planes (the quarter rod of seed 000 section 4.1,
// 7.5 mm cells, step tension 400 MPa): before the crack's centre-of-mass velocity was the nodes'
// momenta over their masses, a node grazed by one particle's support (mass ~ d^2, velocity ~ 1 / d)
// threw the crack's spin fit off and particles beside the crack jumped 20-30 mm in one step (the run
// stopped at step 14, "left the grid"). No particle or crack point can move faster than twice the
// speed behind the incident wave, 2 sigma / (rho c_L) = 17.4 m/s (a free face doubles it): 0.70 mm in
// 40 us; asserted below 1 mm (3D corners run a little faster than the 1D wave).
TEST(Crack3dMotion, UgimpRodWithItsCrackCornerOnTwoSymmetryPlanesRunsAndMovesAtWaveSpeeds) {
  json s = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/rod_elliptical_crack.json");
  s["mpm"]["shape_function"] = "ugimp";
  s["time"]["end"] = 40;  // us (the scene's units)
  s.erase("crack_tips");
  s["output"].erase("tip_interval");
  Model<3> m = build_model<3>(s);
  const std::vector<Vec<3>> x0 = m.particles.x, c0 = m.cracks[0].points;
  auto st = make_stepper<3>(m);
  const long steps = std::lround(40e-6 / m.dt);
  ASSERT_FALSE(test::advance(*st, steps));
  double moved = 0.0, crack_moved = 0.0;
  for (std::size_t p = 0; p < x0.size(); ++p) moved = std::max(moved, (m.particles.x[p] - x0[p]).norm());
  for (std::size_t i = 0; i < c0.size(); ++i) crack_moved = std::max(crack_moved, (m.cracks[0].points[i] - c0[i]).norm());
  std::printf("uGIMP rod, %ld steps to %.3g us: particles moved at most %.3f mm, crack points %.3f mm\n", steps,
              st->time() * 1e6, moved * 1e3, crack_moved * 1e3);
  EXPECT_LT(moved, 1e-3);
  EXPECT_LT(crack_moved, 1e-3);
}

TEST_P(CollidingCrackedBlocks, ConserveMomentumAndKeepTheirCrackFacesApart) {
  const auto [law, detection] = GetParam();
  json s;
  s["analysis"] = {{"type", "3d"}};
  s["grid"] = {{"min", {-0.003, -0.003, -0.003}}, {"max", {0.011, 0.011, 0.016}}, {"cell_size", h}};
  s["mpm"] = {{"shape_function", "linear"}, {"stress_update", "USAVG"}};
  s["materials"] = json::array({test::material("pmma", 3e9, 0.35, 1190)});
  s["bodies"] = json::array(
      {{{"name", "low"}, {"material", "pmma"}, {"shape", {{"type", "box"}, {"min", {0, 0, 0}}, {"max", {0.008, 0.008, 0.006}}}},
        {"velocity", {0, 0, 20}}},
       {{"name", "high"}, {"material", "pmma"}, {"shape", {{"type", "box"}, {"min", {0, 0, 0.006}}, {"max", {0.008, 0.008, 0.012}}}},
        {"velocity", {0, 0, -20}}}});
  json contact = {{"law", law}, {"detection", detection}};
  if (law == "friction") contact["mu"] = 0.3;
  s["cracks"] = json::array(
      {{{"name", "a"}, {"ellipse", {{"center", {0.0041, 0.0039, 0.0035}}, {"normal", {0, 0, 1}}, {"radius", 0.0025}}}, {"contact", contact}},
       {{"name", "b"}, {"ellipse", {{"center", {0.0039, 0.0041, 0.0095}}, {"normal", {0, 0.1, 1}}, {"radius", 0.0025}}}, {"contact", contact}}});
  s["time"] = {{"end", 1.2e-5}, {"cfl", 0.5}};
  Model<3> m = build_model<3>(s);
  const auto& P = m.particles;
  double scale = 0;
  for (std::size_t p = 0; p < P.size(); ++p) scale += P.mass[p] * P.v[p].norm();
  auto st = make_stepper<3>(m);
  double momentum_error = 0, min_gap = 0, max_gap = 0;
  while (st->time() < m.end_time - 1e-9 * m.dt) {
    ASSERT_FALSE(st->step());
    Vec<3> mom = Vec<3>::Zero();
    for (std::size_t p = 0; p < P.size(); ++p) mom += P.mass[p] * P.v[p];
    momentum_error = std::max(momentum_error, mom.norm() / scale);
    for (const auto& c : m.cracks) {
      const std::vector<Vec<3>> n = crack::point_normals(c);
      for (std::size_t i = 0; i < c.points.size(); ++i) {
        const double g = (c.above[i] - c.below[i]).dot(n[i]);
        min_gap = std::min(min_gap, g), max_gap = std::max(max_gap, g);
      }
    }
  }
  std::printf("colliding cracked blocks, %s contact, %s detection: momentum error %.2e, crack-face gap %.4f .. %.4f cells\n",
              law.c_str(), detection.c_str(), momentum_error, min_gap / h, max_gap / h);
  EXPECT_GT(max_gap, 1e-3 * h);  // the reflected tension did open the cracks
  EXPECT_LT(momentum_error, 1e-10);
  EXPECT_GE(min_gap, -0.01 * h);
}

INSTANTIATE_TEST_SUITE_P(LawsAndDetections, CollidingCrackedBlocks,
                         ::testing::Values(LawDetection{"stick", "volume"}, LawDetection{"frictionless", "volume"},
                                           LawDetection{"friction", "volume"}, LawDetection{"stick", "displacement"},
                                           LawDetection{"frictionless", "displacement"},
                                           LawDetection{"friction", "displacement"}),
                         [](const auto& info) { return info.param.first + "_" + info.param.second; });

// Bad input: exit 2 (a SceneError) naming the crack and the reason, before anything runs.
json small_block_with(const json& crack) {
  json s;
  s["analysis"] = {{"type", "3d"}};
  s["grid"] = {{"min", {-0.002, -0.002, -0.002}}, {"max", {0.006, 0.006, 0.006}}, {"cell_size", 1e-3}};
  s["materials"] = json::array({test::material("m", 1e9, 0.3, 1000)});
  s["bodies"] = json::array({{{"name", "b"}, {"material", "m"},
                              {"shape", {{"type", "box"}, {"min", {0, 0, 0}}, {"max", {0.004, 0.004, 0.004}}}}}});
  s["cracks"] = json::array({crack});
  s["time"] = {{"end", 1e-6}};
  return s;
}

TEST(Crack3dInput, BadCrackSurfacesAreRefusedNamingTheCrackAndTheReason) {
  auto refused = [](const json& crack) { return test::error_of([&] { build_model<3>(small_block_with(crack)); }); };
  const json far = {{"name", "far"}, {"ellipse", {{"center", {0.02, 0.02, 0.02}}, {"normal", {0, 0, 1}}, {"radius", 0.001}}}};
  SceneError e = refused(far);
  EXPECT_EQ(e.key_path(), "cracks[0]");
  EXPECT_NE(std::string(e.what()).find("outside every body"), std::string::npos) << e.what();
  const json degenerate = {{"name", "flat"}, {"triangles", {{{0.001, 0.001, 0.0015}, {0.002, 0.002, 0.0015}, {0.003, 0.003, 0.0015}}}}};
  e = refused(degenerate);
  EXPECT_NE(std::string(e.what()).find("triangle 0"), std::string::npos) << e.what();
  const json wide = {{"name", "wide"}, {"rectangle", {{"corner", {-0.0019, 0.001, 0.0015}}, {"edges", {{0.002, 0, 0}, {0, 0.002, 0}}}}},
                     {"element_size", 0.0005}};
  json s = small_block_with(wide);
  s["grid"]["min"] = {-0.001, -0.002, -0.002};  // the crack, kept up to a cell beyond the body, leaves the grid
  e = test::error_of([&] { build_model<3>(s); });
  EXPECT_NE(std::string(e.what()).find("outside the grid"), std::string::npos) << e.what();
  json tips = {{"name", "t"}, {"ellipse", {{"center", {0.002, 0.002, 0.0015}}, {"normal", {0, 0, 1}}, {"radius", 0.001}}},
               {"tips", "both"}};
  e = refused(tips);
  EXPECT_EQ(e.key_path(), "cracks[0].tips");
  tips.erase("tips");
  tips["contact"] = {{"law", "glue"}};
  e = refused(tips);
  EXPECT_EQ(e.key_path(), "cracks[0].contact.law");
  const json missing = {{"name", "f"}, {"file", "/nonexistent/crack.stl"}};
  e = refused(missing);
  EXPECT_EQ(e.key_path(), "cracks[0].file");
}

}  // namespace
}  // namespace cleave
