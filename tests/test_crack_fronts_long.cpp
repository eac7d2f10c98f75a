// The long validations of the crack-front parameters (3D): static K_I of a penny crack and of the
// rod of seed 000 §4.1, and K_I, K_II, K_III of the inclined penny crack of §4.3, each a few minutes
// on two cores. Label "long": not in the README's test
// command (the suite stays well under CI's 20 minutes); run them with
//   ctest --test-dir build -L long
// Figures: docs/validation.md, "Crack-front parameters (3D)".
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "libmpm/crack/front_parameters.hpp"
#include "libmpm/mpm/mpm_method.hpp"
#include "libmpm/mpm/mpm_scene.hpp"
#include "support.hpp"

namespace cleave {
namespace {

using nlohmann::json;
constexpr double kPi = 3.14159265358979323846;

// Validation 1: a penny crack (radius a = 8 cells) in a block, under remote tension, damped to
// static: K_I = 2 sigma sqrt(a / pi) within 5 % at every front node, K_II and K_III below 3 % of
// K_I. Quarter model (symmetry planes x = 0, y = 0: the front's end nodes lie on them), the block's
// half-width and half-height 5a (a 4a block reads 2 % higher, 3a 6 %: its finite size;
// docs/validation.md, figures from bench/crack_fronts/penny_static.py). The default contour (2
// cells) with the out-of-plane term; without it the plane contour reads K_I about
// sqrt(1 + 0.46 r / a) = 5.6 % high on this curved front.
TEST(CrackFrontK, PennyCrackInABlockDampedToStaticGivesKIWithinFivePercentAtEveryFrontNode) {
  Model<3> m = build_model<3>(test::penny_block_scene(5.0));
  auto st = make_stepper<3>(m);
  ASSERT_FALSE(test::advance(*st, std::lround(m.end_time / m.dt)));
  const double K0 = 2 * 10e6 * std::sqrt(0.008 / kPi);
  const auto fronts = st->crack_front_parameters(*m.crack_tips);
  ASSERT_GE(fronts.size(), 20u);
  for (const auto& r : fronts) {
    std::printf("node %2d at (%.2f, %.2f) mm: KI/K0 %.4f, KII/K0 %+.5f, KIII/K0 %+.5f, flag %d\n", r.node, r.x.x() * 1e3,
                r.x.y() * 1e3, r.KI / K0, r.KII / K0, r.KIII / K0, r.flag);
    EXPECT_EQ(r.flag, 0) << "node " << r.node;
    EXPECT_NEAR(r.KI / K0, 1.0, 0.05) << "node " << r.node;
    EXPECT_LT(std::fabs(r.KII), 0.03 * r.KI) << "node " << r.node;
    EXPECT_LT(std::fabs(r.KIII), 0.03 * r.KI) << "node " << r.node;
  }
}

// Validation 3 (its static part): the rod of seed 000 §4.1 with an embedded elliptical crack
// (data/scenes/rod_elliptical_crack.json, quarter model) at the seed's finest cells, 3 mm, damped to
// static: K_I at the deepest point A (x = 0, y = 20 mm, on a symmetry plane) within 3 % of the
// finite rod's 83.6 MPa m^1/2 (validation.md §4). K_I at 240 us is within 0.2 % of its value at 400 us.
TEST(CrackFrontK, RodWithAnEmbeddedEllipticalCrackDampedToStaticGivesKIAtTheDeepestPointWithinThreePercent) {
  json s = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/rod_elliptical_crack.json");
  s["resolution"] = 3;
  s["damping"] = {{"kinetic", 0.05}};  // 1/us
  s["time"]["end"] = 250;
  s.erase("output");
  Model<3> m = build_model<3>(s);
  auto st = make_stepper<3>(m);
  ASSERT_FALSE(test::advance(*st, std::lround(m.end_time / m.dt)));
  const auto fronts = st->crack_front_parameters(*m.crack_tips);
  const auto A = std::min_element(fronts.begin(), fronts.end(), [](const auto& a, const auto& b) {
    return (a.x - Vec<3>(0, 0.02, 0)).norm() < (b.x - Vec<3>(0, 0.02, 0)).norm();
  });
  ASSERT_NE(A, fronts.end());
  ASSERT_LT((A->x - Vec<3>(0, 0.02, 0)).norm(), 1e-4);
  std::printf("K_I at A: %.4g MPa m^1/2 (%+.2f %% of 83.6)\n", A->KI / 1e6, 100 * (A->KI / 83.6e6 - 1));
  EXPECT_EQ(A->flag, 0);
  EXPECT_NEAR(A->KI / 83.6e6, 1.0, 0.03);
}

// Validation 2: the inclined penny crack of seed 000 §4.3 (data/scenes/bar_inclined_penny.json: a
// bar of radius 50 mm, a crack of radius 10 mm at 60 degrees to the load, step tension damped to
// static) at the seed's 2 mm cells and 4 mm contour, t = 600 us: K_I, K_II, K_III at the seed's
// points A (theta = 0 from the direction of shear, and 180) and C (+-90 degrees) within 5 % of K0 of
// Tada's static solution at the node (validation.md §4); nodes lie there. Point B (45 degrees) has
// no node: the eight nodes 3 degrees either side of its four positions are asserted. They read K_I
// -4.44 and -4.98 % of K0, at the criterion's limit (before the opening probes' fix of session 32,
// -4.6 ... -5.2 %); K_I elsewhere along the front goes down to -5.9 % (docs/validation.md). Without
// the out-of-plane term's along-front part (front_along_term.hpp) A read K_I -8.2 %.
TEST(CrackFrontK, InclinedPennyCrackInABarDampedGivesKIKIIKIIIWithinFivePercentOfK0AtAAndCAndBesideB) {
  json s = load_scene_file(CLEAVE_SOURCE_DIR "/data/scenes/bar_inclined_penny.json");
  s.erase("output");
  Model<3> m = build_model<3>(s);
  ASSERT_EQ(m.front_references.size(), 1u);
  auto st = make_stepper<3>(m);
  ASSERT_FALSE(test::advance(*st, std::lround(m.end_time / m.dt)));
  const auto fronts = st->crack_front_parameters(*m.crack_tips);
  ASSERT_EQ(fronts.size(), 60u);
  const auto& ref = m.front_references[0];
  const double K0 = 2 * 40e6 * std::sqrt(0.010 / kPi);
  // theta of a node: its angle in the crack plane from the direction of shear (the rings' start, A).
  const Vec<3> n(0.5, 0, std::sqrt(0.75)), shear(-std::sqrt(0.75), 0, 0.5), other = n.cross(shear);
  const auto theta = [&](const Vec<3>& x) { return std::atan2(x.dot(other), x.dot(shear)) * 180 / kPi; };
  int asserted = 0;
  for (const auto& r : fronts) {
    const auto k = ref.at(crack::front_frame(m.cracks[r.crack], r.front, r.node));
    const double t = theta(r.x);
    const double e[3] = {100 * (std::fabs(r.KI) - std::fabs(k.KI)) / K0, 100 * (std::fabs(r.KII) - std::fabs(k.KII)) / K0,
                         100 * (std::fabs(r.KIII) - std::fabs(k.KIII)) / K0};
    const double off_axis = std::fabs(std::remainder(t, 90.0));  // 0 at A and C
    const double off_b = std::fabs(std::remainder(t - 45.0, 90.0));
    std::printf("node %2d, theta %6.1f: |K|/K0 %.3f %.3f %.3f (Tada %.3f %.3f %.3f), errors in %% of K0 %+.1f %+.1f %+.1f%s, "
                "flag %d\n", r.node, t, std::fabs(r.KI) / K0, std::fabs(r.KII) / K0, std::fabs(r.KIII) / K0,
                std::fabs(k.KI) / K0, std::fabs(k.KII) / K0, std::fabs(k.KIII) / K0, e[0], e[1], e[2],
                off_axis < 0.5 ? (std::fabs(std::remainder(t, 180.0)) < 0.5 ? " (A)" : " (C)") : (off_b < 4 ? " (beside B)" : ""),
                r.flag);
    if (off_axis >= 0.5 && off_b >= 4) continue;
    ++asserted;
    EXPECT_EQ(r.flag, 0);
    for (const double err : e) EXPECT_LT(std::fabs(err), 5.0) << "node " << r.node << " at theta " << t;
  }
  EXPECT_EQ(asserted, 12);  // A at 0 and 180 degrees, C at +-90, two nodes beside each of B's four places
}

}  // namespace
}  // namespace cleave
